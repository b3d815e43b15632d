//! Remembered sightings: what the sensors read at a compass pose, and whether a straight move
//! from it is blocked, kept per thread so that a pose seen before is not cast again.
//!
//! With `actions` motion a robot's position is home plus a sum of 8 mm moves along twelve fixed
//! directions, each added with the same floating-point operations, and its heading is one of
//! twelve. The robots of a run therefore come back to the very same poses, to the last bit, over
//! and over: in a paper-scale study about 94 % of the steps taken near a wall are at a pose some
//! earlier trial on the same thread already stood on. What a pose shows is a pure function of the
//! pose (noise is drawn afterwards), so it is computed once and remembered.
//!
//! A lookup returns exactly the bits the computation returned, so results are identical with or
//! without the memo, whatever the number of threads, the table size or what was evicted. Each
//! thread keeps a table of [`SLOTS`] entries for each of its last [`TABLES`] owners (an arena
//! and a step length); a pose hashes to a set of two slots in one cache line, and a new pose
//! takes the place of the older of the set's two (two ways cost no more memory traffic than
//! one, and a reduced study computes a tenth fewer sights than with one slot per hash). A
//! table whose arena is gone is the first to be taken over by a new owner. The
//! sensor values are whole numbers in 0–1023 (the `sampled` sensor model), which is what lets an
//! entry fit in 32 bytes; the caller must not use the memo for other values.
//!
//! Lookups land all over a table, so with ordinary 4 KiB pages most of them also missed the
//! processor's address cache (TLB). Each table is therefore one 8 MiB block on an 8 MiB
//! boundary, which Linux is asked to back with transparent huge pages (four of 2 MiB). A thread
//! thus keeps at most 64 MiB of tables (the paper's study, five rooms: 40 MiB a thread); a
//! quarter of that size computes about a fifth more sights, which cost a paper-scale study
//! 2–4 % of its time (bench/HISTORY.md, "Shorter chains in the lanes").
//!
//! Which arenas share tables is decided process-wide: arenas equal in every bit a sight reads
//! ([`SightKey`]) hold the same memo number ([`MemoClaim`]) in a registry that forgets a number
//! when its last arena goes; the tables of a forgotten number are taken over first.

use std::alloc::{Layout, alloc, dealloc, handle_alloc_error};
use std::cell::RefCell;
use std::collections::HashMap;
use std::ptr::NonNull;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, LazyLock, Mutex, MutexGuard, PoisonError, Weak};

use crate::simulation::geom::Vec2;
use crate::simulation::sensor::SensorModel;

/// The most sensors a sight holds (a robot with more is never remembered).
pub(crate) const SIGHT_SENSORS: usize = 8;
use SIGHT_SENSORS as INPUTS;

/// Entries per table (2¹⁸: 8 MiB).
pub const SLOTS: usize = 1 << 18;

/// Slots a pose may take (a set: two slots of 32 bytes, one cache line).
const WAYS: usize = 2;

/// Tables per thread: one per arena and step length in use, the oldest replaced first.
pub const TABLES: usize = 8;

/// What a robot at a pose sees and whether it can go straight on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sight {
    /// Noise-free sensor values (0–1023).
    pub sensors: [f64; INPUTS],
    /// Whether a straight move from the pose would overlap a wall.
    pub blocked: bool,
}

impl Sight {
    /// Nothing in sensor range, nothing in the way.
    pub const CLEAR: Sight = Sight {
        sensors: [0.0; INPUTS],
        blocked: false,
    };
}

/// Whose poses a table holds: an arena (by its number) and the length of a straight move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Owner {
    /// The arena's number, the same for equal arenas (see [`crate::simulation::trial::Arena`]'s `memo`).
    pub arena: u64,
    /// The bits of the straight-move length (mm).
    pub step: u64,
}

/// Runs `f` with this thread's table for `owner` (made, or taken over from an owner whose arena
/// is gone — `live(number)` false — or else from the oldest owner, if it has none), borrowed for
/// as long as `f` runs: a trial takes it once, not once per step. `live` is asked only when
/// the thread has no table for `owner`. `f` gets `None` if the thread's tables are already
/// borrowed (a trial run from inside another trial, by its controller or observer): it then
/// computes every sight, with the same results.
pub fn with_table<T>(
    owner: Owner,
    live: fn(u64) -> bool,
    f: impl FnOnce(Option<&mut Table>) -> T,
) -> T {
    MEMO.with(|memo| match memo.try_borrow_mut() {
        Ok(mut memo) => f(Some(memo.table(owner, live))),
        Err(_) => f(None),
    })
}

/// Prefetches `slot` into every cache level.
#[inline(always)]
fn touch(slot: &Slot) {
    #[cfg(target_arch = "x86_64")]
    // SAFETY: a prefetch is only a hint: it never faults and changes no memory, and `slot` is
    // a valid reference besides. SSE (which has the instruction) is part of every x86-64.
    unsafe {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        _mm_prefetch::<_MM_HINT_T0>(std::ptr::from_ref(slot).cast::<i8>());
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = slot;
}

thread_local! {
    static MEMO: RefCell<Memo> = const { RefCell::new(Memo { tables: Vec::new(), next: 0 }) };
}

/// One thread's tables.
struct Memo {
    tables: Vec<Table>,
    /// The table to replace when all [`TABLES`] are in use.
    next: usize,
}

impl Memo {
    /// `owner`'s table; if it has none, the table of an arena no longer `live` is taken over
    /// (emptied), else a new one is made, else the oldest owner's is taken over.
    #[inline]
    fn table(&mut self, owner: Owner, live: fn(u64) -> bool) -> &mut Table {
        if let Some(k) = self.tables.iter().position(|t| t.owner == owner) {
            return &mut self.tables[k];
        }
        let free = self.tables.iter().position(|t| !live(t.owner.arena));
        let k = match free {
            Some(k) => k,
            None if self.tables.len() < TABLES => {
                self.tables.push(Table {
                    owner,
                    slots: Slots::new(),
                });
                return self.tables.last_mut().expect("just pushed");
            }
            None => {
                let k = self.next;
                self.next = (k + 1) % TABLES;
                k
            }
        };
        let table = &mut self.tables[k];
        table.owner = owner;
        table.slots.fill(Slot::EMPTY);
        table
    }
}

/// The poses of one owner, in one thread ([`with_table`]).
pub struct Table {
    owner: Owner,
    slots: Slots,
}

impl Table {
    /// Whose poses this table holds.
    pub fn owner(&self) -> Owner {
        self.owner
    }

    /// The sight remembered for the pose (`pos`, compass direction `dir`), or computed by
    /// `look` and remembered. `look` must return sensor values that are whole numbers in
    /// 0–1023.
    ///
    /// Then asks the processor to fetch the slots of the poses `next` into cache (the poses the
    /// caller may ask for next), so that their lookup does not wait on memory: a table is larger
    /// than the caches, and a lookup is otherwise a cache miss.
    #[inline(always)]
    pub fn recall(
        &mut self,
        pos: Vec2,
        dir: usize,
        next: &[(Vec2, usize)],
        look: impl FnOnce() -> Sight,
    ) -> Sight {
        let key = Key::new(pos, dir);
        let set = self.set(&key);
        // Which way holds the pose is chosen without a branch (it is either, unpredictably);
        // only a miss branches.
        let (first, second) = (set[0].holds(&key), set[1].holds(&key));
        let sight = match first | second {
            true => set[usize::from(!first)].sight(),
            false => {
                let sight = look();
                // The newer of the set's two poses stays; the older makes room.
                set[1] = set[0];
                set[0] = Slot::new(&key, &sight);
                sight
            }
        };
        for &(pos, dir) in next {
            touch(&self.set(&Key::new(pos, dir))[0]);
        }
        sight
    }

    /// The set of [`WAYS`] slots `key` hashes to (one cache line).
    #[inline]
    fn set(&mut self, key: &Key) -> &mut [Slot; WAYS] {
        let k = key.set();
        let set = &mut self.slots[k * WAYS..(k + 1) * WAYS];
        set.try_into().expect("a set is WAYS slots")
    }
}

/// A table's [`SLOTS`] slots: one block of [`Slots::BYTES`] (8 MiB) aligned to its size, so
/// that it is exactly four huge pages, which Linux is asked for (`madvise(MADV_HUGEPAGE)`) before
/// the block is first written. Where the advice is refused or unknown (another system,
/// transparent huge pages switched off) the block is ordinary memory: only speed differs.
struct Slots(NonNull<Slot>);

impl Slots {
    /// The block's size in bytes.
    const BYTES: usize = SLOTS * std::mem::size_of::<Slot>();
    const LAYOUT: Layout = match Layout::from_size_align(Slots::BYTES, Slots::BYTES) {
        Ok(layout) => layout,
        Err(_) => panic!("SLOTS slots make a power-of-two block"),
    };

    /// A block of empty slots.
    fn new() -> Slots {
        // SAFETY: the layout's size is not zero.
        let block = unsafe { alloc(Slots::LAYOUT) };
        let Some(block) = NonNull::new(block.cast::<Slot>()) else {
            handle_alloc_error(Slots::LAYOUT)
        };
        advise_huge_page(block.cast(), Slots::BYTES);
        // The first write faults the pages in, after the advice.
        for k in 0..SLOTS {
            // SAFETY: the block holds SLOTS slots (its layout), aligned for `Slot`.
            unsafe { block.add(k).write(Slot::EMPTY) };
        }
        Slots(block)
    }
}

impl std::ops::Deref for Slots {
    type Target = [Slot];
    fn deref(&self) -> &[Slot] {
        // SAFETY: the block holds SLOTS initialised slots for as long as `self` lives.
        unsafe { std::slice::from_raw_parts(self.0.as_ptr(), SLOTS) }
    }
}

impl std::ops::DerefMut for Slots {
    fn deref_mut(&mut self) -> &mut [Slot] {
        // SAFETY: as in `deref`, and `&mut self` makes this the only reference.
        unsafe { std::slice::from_raw_parts_mut(self.0.as_ptr(), SLOTS) }
    }
}

// SAFETY: a `Slots` owns its block alone, as a `Box<[Slot]>` would, and hands out references
// to it only through `&self` and `&mut self`; `Slot` is plain data.
unsafe impl Send for Slots {}
// SAFETY: as for `Send`: shared access is through `&self` only, which gives `&[Slot]`.
unsafe impl Sync for Slots {}

impl Drop for Slots {
    fn drop(&mut self) {
        // SAFETY: the block was allocated in `Slots::new` with this layout.
        unsafe { dealloc(self.0.as_ptr().cast(), Slots::LAYOUT) }
    }
}

/// Asks Linux to back `len` bytes at `block` with transparent huge pages.
#[cfg(target_os = "linux")]
fn advise_huge_page(block: NonNull<u8>, len: usize) {
    // SAFETY: advice only: the range is one allocation of ours, and madvise changes no data in
    // it. A refusal (huge pages switched off) is harmless, so its result is not needed.
    unsafe { libc::madvise(block.as_ptr().cast(), len, libc::MADV_HUGEPAGE) };
}

/// No advice on other systems.
#[cfg(not(target_os = "linux"))]
fn advise_huge_page(_: NonNull<u8>, _: usize) {}

/// A pose: the bits of its position and its compass direction plus one (0 marks an empty slot).
struct Key {
    x: u64,
    y: u64,
    dir: u16,
}

impl Key {
    #[inline]
    fn new(pos: Vec2, dir: usize) -> Key {
        Key {
            x: pos.x.to_bits(),
            y: pos.y.to_bits(),
            dir: dir as u16 + 1,
        }
    }

    /// The set of a table this pose may be kept in (0..SLOTS / WAYS).
    #[inline]
    fn set(&self) -> usize {
        let h = (self.x ^ self.y.rotate_left(32).wrapping_mul(0xff51_afd7_ed55_8ccd))
            .wrapping_add(u64::from(self.dir))
            .wrapping_mul(0x9e37_79b9_7f4a_7c15);
        (h >> (64 - (SLOTS / WAYS).trailing_zeros())) as usize
    }
}

/// One remembered pose in 32 bytes: the position's bits, then the eight sensor values (10 bits
/// each), with the direction plus one in bits 12–15 of the first and `blocked` in its bit 10.
#[derive(Clone, Copy)]
#[repr(C, align(32))]
struct Slot {
    x: u64,
    y: u64,
    values: [u16; INPUTS],
}

const VALUE_BITS: u16 = 0x3ff;
const BLOCKED_BIT: u16 = 1 << 10;
const DIR_SHIFT: u16 = 12;

impl Slot {
    const EMPTY: Slot = Slot {
        x: 0,
        y: 0,
        values: [0; INPUTS],
    };

    fn new(key: &Key, sight: &Sight) -> Slot {
        let mut values = sight.sensors.map(|v| {
            debug_assert!(v.fract() == 0.0 && (0.0..=1023.0).contains(&v), "{v}");
            v as u16
        });
        values[0] |= key.dir << DIR_SHIFT;
        if sight.blocked {
            values[0] |= BLOCKED_BIT;
        }
        Slot {
            x: key.x,
            y: key.y,
            values,
        }
    }

    /// Whether this slot holds the pose `key`: its bits XORed and ORed, so that the compiler
    /// makes no branch of each comparison (which of a set's two slots holds a pose is
    /// unpredictable).
    #[inline]
    fn holds(&self, key: &Key) -> bool {
        let dir = u64::from((self.values[0] >> DIR_SHIFT) ^ key.dir);
        ((self.x ^ key.x) | (self.y ^ key.y) | dir) == 0
    }

    /// The sight this slot holds.
    #[inline]
    fn sight(&self) -> Sight {
        Sight {
            sensors: self.values.map(|v| f64::from(v & VALUE_BITS)),
            blocked: self.values[0] & BLOCKED_BIT != 0,
        }
    }

    /// The sight of the pose `key`, if this slot holds it.
    #[cfg(test)]
    fn read(&self, key: &Key) -> Option<Sight> {
        self.holds(key).then(|| self.sight())
    }
}

// The process-wide registry of memo numbers: which arenas share tables.

/// Everything a sight ([`Arena::sight`](crate::simulation::trial::Arena::sight)) reads of an arena, to the bit: the walls, the grid
/// they are culled to, the compass (the home heading), the sensor model, the body radius and
/// the culling reach (the length of a straight move is the table's, [`Owner::step`]). Arenas
/// with equal keys see the same from every pose, so they may share their memo tables; arenas
/// with different keys never do.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(super) struct SightKey {
    /// Each wall's end points, `[a.x, a.y, b.x, b.y]`.
    pub(super) walls: Vec<[u64; 4]>,
    /// The grid's origin `[x, y]`, columns and rows.
    pub(super) grid: [u64; 4],
    pub(super) heading: u64,
    pub(super) sensor_model: SensorModel,
    pub(super) radius: u64,
    pub(super) near_reach: u64,
}

/// A memo number in use, held by the arenas of one [`SightKey`] (and their clones): when the
/// last of them goes, so does the number's entry in [`REGISTRY`]. Numbers are never given
/// twice, so a table of a number no arena holds any more is never looked at again; threads
/// take such tables over first ([`memo_live`]).
#[derive(Debug)]
pub(super) struct MemoClaim {
    pub(super) number: u64,
    key: SightKey,
}

/// The memo numbers of the arenas alive, by [`SightKey`]: arenas equal in every bit a sight
/// reads (the same room prepared with the same parameters, in several runs or experiments at
/// once) get the same number, and so share their tables. An entry goes when its last arena
/// does ([`MemoClaim`]'s `Drop`), so the registry holds only the keys of arenas alive.
static REGISTRY: LazyLock<Mutex<Registry>> = LazyLock::new(Default::default);

/// Each key's memo number and the claim that holds it.
type Registry = HashMap<SightKey, (u64, Weak<MemoClaim>)>;

/// The next memo number to give (numbers start at 1 and are never reused).
static NEXT_NUMBER: AtomicU64 = AtomicU64::new(1);

/// The registry, locked (a panic elsewhere while it was held leaves it consistent: every
/// change is one map operation).
pub(super) fn registry() -> MutexGuard<'static, Registry> {
    REGISTRY.lock().unwrap_or_else(PoisonError::into_inner)
}

impl MemoClaim {
    /// The claim of the arenas of `key`: the one held by a live arena of the same key, or a
    /// new number.
    pub(super) fn of(key: SightKey) -> Arc<MemoClaim> {
        let mut known = registry();
        if let Some(claim) = known.get(&key).and_then(|(_, weak)| weak.upgrade()) {
            return claim;
        }
        let number = NEXT_NUMBER.fetch_add(1, Ordering::Relaxed);
        let claim = Arc::new(MemoClaim {
            number,
            key: key.clone(),
        });
        known.insert(key, (number, Arc::downgrade(&claim)));
        claim
    }
}

impl Drop for MemoClaim {
    fn drop(&mut self) {
        let mut known = registry();
        // A new claim may already have replaced this one (made between the last arena's
        // going and this drop): its entry stays.
        if known.get(&self.key).is_some_and(|(n, _)| *n == self.number) {
            known.remove(&self.key);
        }
    }
}

/// Whether memo number `number` is held by an arena alive (the others' tables are free).
pub(super) fn memo_live(number: u64) -> bool {
    registry().values().any(|(n, _)| *n == number)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One lookup in this thread's table for `owner`.
    fn recall(
        owner: Owner,
        pos: Vec2,
        dir: usize,
        next: &[(Vec2, usize)],
        look: impl FnOnce() -> Sight,
    ) -> Sight {
        with_table(
            owner,
            |_| true,
            |table| table.expect("not borrowed").recall(pos, dir, next, look),
        )
    }

    /// A table's slots are one block aligned to its size, empty, and each can be written.
    #[test]
    fn slots_are_one_aligned_block() {
        let mut slots = Slots::new();
        assert_eq!(slots.len(), SLOTS);
        assert_eq!(slots.as_ptr() as usize % Slots::BYTES, 0);
        assert_eq!(Slots::BYTES, 8 << 20);
        let key = Key::new(Vec2::new(1.5, -2.0), 3);
        assert!(slots.iter().all(|s| s.read(&key).is_none()));
        let last = SLOTS - 1;
        slots[last] = Slot::new(&key, &sight(5));
        assert_eq!(slots[last].read(&key), Some(sight(5)));
        assert!(slots[0].read(&key).is_none());
    }

    /// A table asked for while this thread's tables are borrowed is refused, not shared.
    #[test]
    fn a_nested_borrow_gets_no_table() {
        let owner = Owner { arena: 4, step: 0 };
        let live: fn(u64) -> bool = |_| true;
        with_table(owner, live, |outer| {
            assert!(outer.is_some());
            with_table(owner, live, |inner| assert!(inner.is_none()));
        });
        with_table(owner, live, |again| assert!(again.is_some()));
    }

    fn sight(k: u16) -> Sight {
        let mut sensors = [0.0; INPUTS];
        sensors[k as usize % INPUTS] = f64::from(1023 - k % 1024);
        sensors[(k as usize + 3) % INPUTS] = f64::from(k % 7);
        Sight {
            sensors,
            blocked: k % 2 == 1,
        }
    }

    /// Every pose reads back what was computed for it, whichever poses share its slot, and a
    /// pose is computed once while it stays in its slot.
    #[test]
    fn recalls_exactly_what_was_computed() {
        let owner = Owner {
            arena: 1,
            step: 8f64.to_bits(),
        };
        let poses: Vec<(Vec2, usize)> = (0..3000)
            .map(|k| {
                (
                    Vec2::new(100.0 + k as f64 * 0.25, 7.0 - k as f64 / 3.0),
                    k % 12,
                )
            })
            .collect();
        for round in 0..2 {
            let mut computed = 0;
            for (k, &(p, dir)) in poses.iter().enumerate() {
                let got = recall(owner, p, dir, &[], || {
                    computed += 1;
                    sight(k as u16)
                });
                assert_eq!(got, sight(k as u16));
            }
            // 3000 poses in 65 536 slots: a few may collide, most are remembered.
            let expected = if round == 0 { 3000..=3000 } else { 0..=299 };
            assert!(
                expected.contains(&computed),
                "round {round}: {computed} computed"
            );
        }
        // Another owner does not see these poses.
        let other = Owner { arena: 2, ..owner };
        let mut computed = false;
        recall(other, poses[0].0, poses[0].1, &[], || {
            computed = true;
            Sight::CLEAR
        });
        assert!(computed);
    }

    /// Two poses of the same set are both remembered; a third takes the place of the older.
    #[test]
    fn a_set_keeps_its_two_newest_poses() {
        let owner = Owner { arena: 5, step: 0 };
        let mut by_set = HashMap::new();
        let same: Vec<Vec2> = (0..)
            .map(|k| Vec2::new(k as f64 * 0.5, 1.0))
            .find_map(|p| {
                let poses: &mut Vec<Vec2> = by_set.entry(Key::new(p, 0).set()).or_default();
                poses.push(p);
                (poses.len() == 3).then(|| poses.clone())
            })
            .expect("three poses share a set");
        let [a, b, c] = [same[0], same[1], same[2]];
        assert_eq!(recall(owner, a, 0, &[], || sight(1)), sight(1));
        assert_eq!(recall(owner, b, 0, &[], || sight(2)), sight(2));
        assert_eq!(recall(owner, a, 0, &[], || unreachable!()), sight(1));
        assert_eq!(recall(owner, b, 0, &[], || unreachable!()), sight(2));
        assert_eq!(recall(owner, c, 0, &[], || sight(3)), sight(3));
        assert_eq!(recall(owner, b, 0, &[], || unreachable!()), sight(2));
        assert_eq!(recall(owner, c, 0, &[], || unreachable!()), sight(3));
        assert_eq!(recall(owner, a, 0, &[], || sight(4)), sight(4));
    }

    /// Positions differing in the last bit, or directions, are different poses.
    #[test]
    fn nearby_poses_are_distinct() {
        let owner = Owner { arena: 3, step: 0 };
        let p = Vec2::new(123.456, 78.9);
        let q = Vec2::new(f64::from_bits(p.x.to_bits() + 1), p.y);
        assert_eq!(recall(owner, p, 4, &[], || sight(1)), sight(1));
        assert_eq!(recall(owner, q, 4, &[], || sight(2)), sight(2));
        assert_eq!(recall(owner, p, 5, &[], || sight(3)), sight(3));
        assert_eq!(recall(owner, p, 4, &[], || unreachable!()), sight(1));
    }

    /// A table whose arena is gone is taken over by the next new owner, emptied, before any
    /// new table is made: the tables of dropped arenas do not pile up.
    #[test]
    fn a_gone_arenas_table_is_taken_over() {
        let gone = Owner {
            arena: 1 << 40,
            step: 0,
        };
        let tables = || MEMO.with(|m| m.borrow().tables.len());
        let p = Vec2::new(1.0, 2.0);
        with_table(
            gone,
            |_| true,
            |t| {
                t.unwrap().recall(p, 0, &[], || sight(1));
            },
        );
        let before = tables();
        for k in 1..=3 * TABLES as u64 {
            let next = Owner {
                arena: (1 << 40) + k,
                step: 0,
            };
            // No earlier owner's arena is alive: each new owner takes a table over.
            with_table(
                next,
                |_| false,
                |t| {
                    let t = t.unwrap();
                    assert_eq!(t.owner(), next);
                    assert_eq!(t.recall(p, 0, &[], || sight(2)), sight(2), "emptied");
                },
            );
            assert_eq!(tables(), before);
        }
    }
}
