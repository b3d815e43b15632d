//! Room recognition from environment vectors: SOM r-node gating plus nearest stored vector
//! (docs/model.md §9), a plain 1-nearest-neighbour for the online mode (docs/model.md §10), and confusion counts.

use crate::modelling::som::{Som, SomError, SomParams, sq_dist};
use crate::random::rng::Rng;

/// One stored room instance: its environment vector and its winning SOM node (r-node).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RoomInstance {
    /// Index of the room in the caller's room list.
    pub room: usize,
    /// The instance's environment vector.
    pub vector: Vec<f64>,
    /// The SOM node that wins for `vector` (its r-node).
    pub r_node: usize,
}

/// A trained recognizer: the SOM, the stored room instances and the r-node gating threshold.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Recognizer {
    /// The map used to find a test vector's winning node.
    pub som: Som,
    /// Stored instances; recognition considers only those with an r-node near the test winner.
    pub instances: Vec<RoomInstance>,
    /// Maximum distance in node indices between an instance's r-node and the test vector's
    /// winner for the instance to be a candidate (`|r_node − r| <= threshold`; default 10).
    pub threshold: usize,
}

impl Recognizer {
    /// Trains the SOM on one vector per room (`vectors[i]` belongs to room `i`) and stores each
    /// vector as an instance with its r-node. Errors as [`Som::train`] (empty set, mismatched
    /// or zero lengths, non-finite values, invalid parameters).
    pub fn train<R: Rng + ?Sized>(
        vectors: &[Vec<f64>],
        params: &SomParams,
        threshold: usize,
        rng: &mut R,
    ) -> Result<Recognizer, SomError> {
        let som = Som::train(vectors, params, rng)?;
        let instances = vectors
            .iter()
            .enumerate()
            .map(|(room, v)| {
                Ok(RoomInstance {
                    room,
                    vector: v.clone(),
                    r_node: som.winner(v)?,
                })
            })
            .collect::<Result<Vec<_>, SomError>>()?;
        Ok(Recognizer {
            som,
            instances,
            threshold,
        })
    }

    /// Assembles a recognizer from an existing map and instances (no checks; mismatches are
    /// reported by [`Recognizer::recognise`]).
    pub fn from_parts(som: Som, instances: Vec<RoomInstance>, threshold: usize) -> Self {
        Recognizer {
            som,
            instances,
            threshold,
        }
    }

    /// The recognised room (the `room` of the chosen instance), or `None` when no instance's
    /// r-node is within `threshold` nodes of `v`'s winner. Among candidates, the instance with
    /// the nearest stored vector (Euclidean) wins. An exact tie between instances of different
    /// rooms is `None` too: a robot whose vectors are identical in several rooms cannot tell
    /// them apart (the paper's "first room wins" would credit the first room in the list).
    /// Errors if `v` or a candidate's vector does not match the map's dimension.
    pub fn recognise(&self, v: &[f64]) -> Result<Option<usize>, SomError> {
        let r = self.som.winner(v)?;
        Ok(self.choose(v, r)?.map(|(inst, _)| inst.room))
    }

    /// Why [`Recognizer::recognise`] answers as it does for `v`: the SOM's winning node and,
    /// when a room is recognised, the chosen instance, its r-node's distance from the winner
    /// (within the gate, `threshold`) and the Euclidean distance of `v` to its stored vector.
    /// The room is always [`Recognizer::recognise`]'s; errors as it does.
    pub fn explain(&self, v: &[f64]) -> Result<Explanation, SomError> {
        let winner = self.som.winner(v)?;
        let chosen = self.choose(v, winner)?.map(|(inst, d)| Chosen {
            room: inst.room,
            r_node: inst.r_node,
            node_distance: inst.r_node.abs_diff(winner),
            vector_distance: d.sqrt(),
        });
        Ok(Explanation {
            winner,
            threshold: self.threshold,
            chosen,
        })
    }

    /// The candidate instance (r-node within `threshold` of the winner `r`) nearest to `v`,
    /// with its squared distance (∞ for NaN); `None` when there is none or rooms tie.
    fn choose(&self, v: &[f64], r: usize) -> Result<Option<(&RoomInstance, f64)>, SomError> {
        let mut best: Option<(&RoomInstance, f64)> = None;
        let mut tied = false;
        for inst in &self.instances {
            if inst.r_node.abs_diff(r) > self.threshold {
                continue;
            }
            if inst.vector.len() != v.len() {
                return Err(SomError::DimensionMismatch {
                    expected: v.len(),
                    found: inst.vector.len(),
                });
            }
            // A NaN distance (NaN input) ranks as infinitely far.
            let d = sq_dist(&inst.vector, v);
            let d = if d.is_nan() { f64::INFINITY } else { d };
            match best {
                Some((_, bd)) if d > bd => {}
                // An exact tie between different rooms: the nearest room is undefined.
                Some((b, bd)) if d == bd && b.room != inst.room => tied = true,
                Some((_, bd)) if d == bd => {}
                _ => {
                    best = Some((inst, d));
                    tied = false;
                }
            }
        }
        Ok(if tied { None } else { best })
    }
}

/// [`Recognizer::explain`]'s answer: the SOM's gate and nearest-neighbour step for one vector.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Explanation {
    /// The SOM's winning node for the vector.
    pub winner: usize,
    /// The gate's width: an instance is a candidate when its r-node lies within this many
    /// nodes of the winner.
    pub threshold: usize,
    /// The instance recognised, none when no r-node passes the gate or rooms tie.
    pub chosen: Option<Chosen>,
}

/// The instance a vector is recognised as (see [`Explanation`]).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Chosen {
    /// Its room (an index into the caller's room list).
    pub room: usize,
    /// Its r-node.
    pub r_node: usize,
    /// `|winner − r_node|`, in nodes: at most the gate's width.
    pub node_distance: usize,
    /// The Euclidean distance of the vector to the instance's stored vector (∞ for NaN).
    pub vector_distance: f64,
}

/// The reference nearest to `v`, or `None` when two or more references tie at the smallest
/// distance (used by online orientation, where each reference is one room).
pub fn nearest_unique(references: &[Vec<f64>], v: &[f64]) -> Result<Option<usize>, SomError> {
    let best = nearest(references, v)?;
    let d = sq_dist(&references[best], v);
    let ties = references.iter().filter(|r| sq_dist(r, v) == d).count();
    Ok((ties == 1).then_some(best))
}

/// Index of the reference nearest to `v` (Euclidean, ties → lowest index).
///
/// Errors: [`SomError::EmptyData`] if `references` is empty, [`SomError::DimensionMismatch`]
/// if any reference's length differs from `v`'s. References at NaN distance never win unless
/// all are NaN (then 0).
pub fn nearest(references: &[Vec<f64>], v: &[f64]) -> Result<usize, SomError> {
    if references.is_empty() {
        return Err(SomError::EmptyData);
    }
    let mut best = 0;
    let mut best_d = f64::INFINITY;
    for (i, r) in references.iter().enumerate() {
        if r.len() != v.len() {
            return Err(SomError::DimensionMismatch {
                expected: v.len(),
                found: r.len(),
            });
        }
        let d = sq_dist(r, v);
        if d < best_d {
            best_d = d;
            best = i;
        }
    }
    Ok(best)
}

/// Confusion counts of a recognition test: row = true room, column = recognised room, with an
/// extra last column (index `rooms`) for "not recognised".
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Confusion {
    /// Number of rooms.
    pub rooms: usize,
    /// `rooms × (rooms + 1)` counts; `counts[t][a]` = trials of true room `t` answered `a`,
    /// `counts[t][rooms]` = trials of room `t` not recognised.
    pub counts: Vec<Vec<u32>>,
}

impl Confusion {
    /// An all-zero table for `rooms` rooms.
    pub fn new(rooms: usize) -> Self {
        Confusion {
            rooms,
            counts: vec![vec![0; rooms + 1]; rooms],
        }
    }

    /// Counts one trial of true room `truth` answered `answer` (`None` = not recognised).
    /// A `truth` out of range is ignored; an `answer` out of range counts as not recognised.
    /// Counts saturate at `u32::MAX`.
    pub fn record(&mut self, truth: usize, answer: Option<usize>) {
        let col = match answer {
            Some(a) if a < self.rooms => a,
            _ => self.rooms,
        };
        if let Some(c) = self.counts.get_mut(truth).and_then(|row| row.get_mut(col)) {
            *c = c.saturating_add(1);
        }
    }

    /// Trials of `room` recognised correctly (0 if `room` is out of range).
    pub fn correct(&self, room: usize) -> u32 {
        self.counts
            .get(room)
            .and_then(|row| row.get(room))
            .copied()
            .unwrap_or(0)
    }

    /// All trials of `room`, including not recognised (0 if `room` is out of range; saturating).
    pub fn total(&self, room: usize) -> u32 {
        self.counts
            .get(room)
            .map(|row| row.iter().fold(0u32, |s, &c| s.saturating_add(c)))
            .unwrap_or(0)
    }

    /// Percentage (0–100) of `room`'s trials recognised correctly; 0 when it has no trials.
    pub fn percent(&self, room: usize) -> f64 {
        let total = self.total(room);
        if total == 0 {
            0.0
        } else {
            100.0 * f64::from(self.correct(room)) / f64::from(total)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::rng::rng_from_seed;

    /// A 1-D map with 10 nodes whose weights are 0, 1, …, 9.
    fn line_som() -> Som {
        Som::from_weights(10, 1, (0..10).map(f64::from).collect()).unwrap()
    }

    #[test]
    fn trained_instances_recognised() {
        let vectors: Vec<Vec<f64>> = (0..4)
            .map(|r| (0..20).map(|t| (t * (r + 1)) as f64 / 12.0).collect())
            .collect();
        let p = SomParams::from_raw(&crate::modelling::som::RawSom {
            nodes: 32,
            epochs: 100,
            sigma_start: 8.0,
            ..Default::default()
        })
        .unwrap();
        let rec = Recognizer::train(&vectors, &p, 10, &mut rng_from_seed(5)).unwrap();
        assert_eq!(rec.instances.len(), 4);
        for (i, v) in vectors.iter().enumerate() {
            assert_eq!(rec.instances[i].room, i);
            assert_eq!(rec.instances[i].r_node, rec.som.winner(v).unwrap());
            assert_eq!(rec.recognise(v).unwrap(), Some(i));
        }
    }

    #[test]
    fn far_winner_not_recognised() {
        let inst = vec![
            RoomInstance {
                room: 0,
                vector: vec![0.0],
                r_node: 0,
            },
            RoomInstance {
                room: 1,
                vector: vec![1.0],
                r_node: 1,
            },
        ];
        let rec = Recognizer::from_parts(line_som(), inst.clone(), 0);
        assert_eq!(rec.recognise(&[9.0]).unwrap(), None);
        assert_eq!(rec.recognise(&[0.1]).unwrap(), Some(0));
        let rec = Recognizer::from_parts(line_som(), inst, 10);
        assert_eq!(rec.recognise(&[9.0]).unwrap(), Some(1));
        let empty = Recognizer::from_parts(line_som(), vec![], 10);
        assert_eq!(empty.recognise(&[3.0]).unwrap(), None);
    }

    #[test]
    fn explain_gives_the_gate_and_the_nearest_step_of_recognise() {
        let inst = vec![
            RoomInstance {
                room: 0,
                vector: vec![5.4],
                r_node: 0,
            },
            RoomInstance {
                room: 1,
                vector: vec![0.0],
                r_node: 5,
            },
            RoomInstance {
                room: 2,
                vector: vec![-3.0],
                r_node: 6,
            },
            RoomInstance {
                room: 3,
                vector: vec![3.0],
                r_node: 6,
            },
        ];
        let rec = Recognizer::from_parts(line_som(), inst, 1);
        // 5.0 wins node 5: rooms 1, 2, 3 pass the gate, room 3's vector is nearest (2.0 away).
        let e = rec.explain(&[5.0]).unwrap();
        assert_eq!((e.winner, e.threshold), (5, 1));
        assert_eq!(
            e.chosen,
            Some(Chosen {
                room: 3,
                r_node: 6,
                node_distance: 1,
                vector_distance: 2.0
            })
        );
        // 9.0 wins node 9: no r-node within 1 node.
        assert_eq!(rec.explain(&[9.0]).unwrap().chosen, None);
        // Whatever the vector, explain's room is recognise's.
        for x in [
            -4.0,
            -1.0,
            0.0,
            1.5,
            2.7,
            3.0,
            4.2,
            5.0,
            5.5,
            6.0,
            7.0,
            9.0,
            f64::NAN,
        ] {
            let e = rec.explain(&[x]).unwrap();
            assert_eq!(
                e.chosen.map(|c| c.room),
                rec.recognise(&[x]).unwrap(),
                "{x}"
            );
            assert_eq!(e.winner, rec.som.winner(&[x]).unwrap(), "{x}");
        }
        let tied = Recognizer::from_parts(
            line_som(),
            vec![
                RoomInstance {
                    room: 0,
                    vector: vec![4.0],
                    r_node: 5,
                },
                RoomInstance {
                    room: 1,
                    vector: vec![6.0],
                    r_node: 5,
                },
            ],
            10,
        );
        assert_eq!(tied.explain(&[5.0]).unwrap().chosen, None);
        assert!(tied.explain(&[5.5]).unwrap().chosen.is_some());
    }

    #[test]
    fn nearest_candidate_wins_over_nearest_overall() {
        // Instance 0 is nearest to the test vector but its r-node is outside the threshold.
        let inst = vec![
            RoomInstance {
                room: 0,
                vector: vec![5.4],
                r_node: 0,
            },
            RoomInstance {
                room: 1,
                vector: vec![0.0],
                r_node: 5,
            },
            RoomInstance {
                room: 2,
                vector: vec![-3.0],
                r_node: 6,
            },
        ];
        let rec = Recognizer::from_parts(line_som(), inst, 1);
        // Winner of 5.0 is node 5; candidates are rooms 1 and 2; room 1 is nearer.
        assert_eq!(rec.recognise(&[5.0]).unwrap(), Some(1));
    }

    #[test]
    fn ties_between_rooms_are_not_recognised() {
        let inst = vec![
            RoomInstance {
                room: 7,
                vector: vec![2.0],
                r_node: 3,
            },
            RoomInstance {
                room: 3,
                vector: vec![4.0],
                r_node: 3,
            },
        ];
        let rec = Recognizer::from_parts(line_som(), inst.clone(), 10);
        // Equidistant from rooms 7 and 3: undefined, so not recognised.
        assert_eq!(rec.recognise(&[3.0]).unwrap(), None);
        assert_eq!(rec.recognise(&[2.5]).unwrap(), Some(7));
        // Two instances of the same room tying is fine.
        let mut same = inst;
        same[1].room = 7;
        let rec = Recognizer::from_parts(line_som(), same, 10);
        assert_eq!(rec.recognise(&[3.0]).unwrap(), Some(7));
        assert_eq!(nearest(&[vec![2.0], vec![4.0]], &[3.0]).unwrap(), 0);
        assert_eq!(
            nearest_unique(&[vec![2.0], vec![4.0]], &[3.0]).unwrap(),
            None
        );
        assert_eq!(
            nearest_unique(&[vec![2.0], vec![4.0]], &[3.5]).unwrap(),
            Some(1)
        );
    }

    #[test]
    fn nearest_plain() {
        let refs = vec![vec![0.0, 0.0], vec![1.0, 1.0], vec![5.0, 5.0]];
        assert_eq!(nearest(&refs, &[0.9, 1.2]).unwrap(), 1);
        assert_eq!(nearest(&refs, &[4.0, 9.0]).unwrap(), 2);
        assert_eq!(nearest(&refs, &[-1.0, 0.0]).unwrap(), 0);
    }

    #[test]
    fn errors() {
        assert_eq!(nearest(&[], &[1.0]), Err(SomError::EmptyData));
        assert_eq!(
            nearest(&[vec![1.0], vec![1.0, 2.0]], &[1.0]),
            Err(SomError::DimensionMismatch {
                expected: 1,
                found: 2
            })
        );
        let mut rng = rng_from_seed(0);
        let p = SomParams::default();
        assert_eq!(
            Recognizer::train(&[], &p, 10, &mut rng),
            Err(SomError::EmptyData)
        );
        assert_eq!(
            Recognizer::train(&[vec![1.0], vec![1.0, 2.0]], &p, 10, &mut rng),
            Err(SomError::DimensionMismatch {
                expected: 1,
                found: 2
            })
        );
        let rec = Recognizer::from_parts(
            line_som(),
            vec![RoomInstance {
                room: 0,
                vector: vec![1.0, 2.0],
                r_node: 1,
            }],
            10,
        );
        assert_eq!(
            rec.recognise(&[1.0, 2.0]),
            Err(SomError::DimensionMismatch {
                expected: 1,
                found: 2
            })
        );
        assert_eq!(
            rec.recognise(&[1.0]),
            Err(SomError::DimensionMismatch {
                expected: 1,
                found: 2
            })
        );
    }

    #[test]
    fn confusion_counts_and_percent() {
        let mut c = Confusion::new(3);
        c.record(0, Some(0));
        c.record(0, Some(0));
        c.record(0, Some(1));
        c.record(0, None);
        c.record(1, Some(1));
        c.record(2, Some(99)); // out of range → not recognised
        c.record(5, Some(0)); // unknown truth → ignored
        assert_eq!(
            c.counts,
            vec![vec![2, 1, 0, 1], vec![0, 1, 0, 0], vec![0, 0, 0, 1]]
        );
        assert_eq!((c.correct(0), c.total(0)), (2, 4));
        assert_eq!(c.percent(0), 50.0);
        assert_eq!(c.percent(1), 100.0);
        assert_eq!(c.percent(2), 0.0);
        assert_eq!((c.correct(9), c.total(9), c.percent(9)), (0, 0, 0.0));
        assert_eq!(Confusion::new(2).percent(0), 0.0);
    }
}
