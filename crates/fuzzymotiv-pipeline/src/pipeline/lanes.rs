//! Runs side by side: a study's runs or a sweep's jobs as many at a time as there are threads
//! ([`run_concurrently`]), on the pool `--threads` sizes ([`set_threads`]).

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use crate::files::error::CliError;
use crate::files::inputs::check_threads;

/// Configures rayon's global pool: `--threads` from 1 to
/// [`MAX_THREADS`](crate::files::inputs::MAX_THREADS) (the commands' parser
/// [`parse_threads`](crate::files::inputs::parse_threads) already checked it; a library caller
/// gets the same message).
pub fn set_threads(threads: Option<usize>) -> Result<(), CliError> {
    if let Some(n) = threads {
        let n = check_threads(n as i128).map_err(|m| CliError::input(format!("--threads {m}")))?;
        // A second call (e.g. in-process tests) keeps the first pool; results do not depend on it.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global();
    }
    Ok(())
}

/// Runs `job` on every item, as many at a time as the thread pool has threads (one at a time
/// with `--threads 1`): one lane per thread ([`rayon::broadcast`]), each taking the next item
/// until none is left. Each item (a run) also evaluates its populations in parallel, so a thread
/// whose own run waits at the end of a generation takes work from the others, and no core idles
/// while one run trains its maps or writes its files. Results come in item order and do not
/// depend on the timing: items are independent. After an error or a panic no new item starts;
/// the first error in item order is returned (a panic goes on once the lanes have stopped).
pub fn run_concurrently<T, R>(
    items: &[T],
    job: impl Fn(&T) -> Result<R, CliError> + Sync,
) -> Result<Vec<R>, CliError>
where
    T: Sync,
    R: Send,
{
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let results: Vec<Mutex<Option<Result<R, CliError>>>> =
        items.iter().map(|_| Default::default()).collect();
    rayon::broadcast(|_| {
        let _on_panic = StopOnPanic(&stop);
        while !stop.load(Ordering::Relaxed) {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(item) = items.get(k) else { break };
            let result = job(item);
            stop.fetch_or(result.is_err(), Ordering::Relaxed);
            *results[k].lock().unwrap_or_else(PoisonError::into_inner) = Some(result);
        }
    });
    results
        .into_iter()
        .filter_map(|r| r.into_inner().unwrap_or_else(PoisonError::into_inner))
        .collect()
}

/// Tells the other lanes of [`run_concurrently`] to start nothing new when its lane panics.
struct StopOnPanic<'a>(&'a AtomicBool);

impl Drop for StopOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.store(true, Ordering::Relaxed);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pool(threads: usize) -> rayon::ThreadPool {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
    }

    /// Results come in item order whatever the number of threads, and the items really run
    /// side by side when there are threads for it.
    #[test]
    fn runs_come_back_in_item_order() {
        let items: Vec<u64> = (0..9).collect();
        for threads in [1, 2, 4] {
            let at_once = AtomicUsize::new(0);
            let most = AtomicUsize::new(0);
            let got = pool(threads).install(|| {
                run_concurrently(&items, |&k| {
                    let now = at_once.fetch_add(1, Ordering::SeqCst) + 1;
                    most.fetch_max(now, Ordering::SeqCst);
                    std::thread::sleep(std::time::Duration::from_millis(20));
                    at_once.fetch_sub(1, Ordering::SeqCst);
                    Ok(k * k)
                })
            });
            assert_eq!(
                got.unwrap(),
                items.iter().map(|k| k * k).collect::<Vec<_>>()
            );
            let most = most.into_inner();
            assert!(most <= threads, "{most} at once on {threads} threads");
            assert!(
                threads == 1 || most >= 2,
                "never two at once on {threads} threads"
            );
        }
    }

    /// The first error in item order is returned; no item starts after an error.
    #[test]
    fn the_first_error_in_item_order_is_returned() {
        let items: Vec<usize> = (0..40).collect();
        let started = AtomicUsize::new(0);
        let got = pool(2).install(|| {
            run_concurrently(&items, |&k| {
                started.fetch_add(1, Ordering::SeqCst);
                if k == 3 || k == 5 {
                    Err(CliError::runtime(format!("item {k} failed")))
                } else {
                    Ok(k)
                }
            })
        });
        let message = got.expect_err("an error").to_string();
        assert!(message.contains("item 3 failed"), "{message}");
        assert!(
            started.into_inner() < items.len(),
            "items started after the error"
        );
    }

    /// A panic in one lane stops the others from starting new items, then goes on.
    #[test]
    fn a_panic_stops_new_items() {
        let items: Vec<usize> = (0..40).collect();
        let started = AtomicUsize::new(0);
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool(2).install(|| {
                run_concurrently(&items, |&k| {
                    started.fetch_add(1, Ordering::SeqCst);
                    assert_ne!(k, 2, "item 2 panics");
                    // Long enough to outlast the panic hook (a backtrace takes a while).
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    Ok(k)
                })
            })
        }));
        assert!(outcome.is_err(), "the panic goes on");
        let started = started.into_inner();
        assert!(started < items.len(), "all {started} items started");
    }
}
