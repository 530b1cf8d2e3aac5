//! Work on two threads, for the few places where it pays (the split factorization, closest
//! points): scoped threads of the standard library, no pool.

use std::sync::Mutex;

/// Runs `first` on a second thread and `second` on this one (both here, one after the other,
/// when no thread can be started).
pub fn both<A: Send, B>(first: impl FnOnce() -> A + Send, second: impl FnOnce() -> B) -> (A, B) {
    let (a, b, _) = both_telling(first, second);
    (a, b)
}

/// [`both`], and whether `first` did run on a second thread.
pub fn both_telling<A: Send, B>(
    first: impl FnOnce() -> A + Send,
    second: impl FnOnce() -> B,
) -> (A, B, bool) {
    let slot = Mutex::new(Some(first));
    let run = || {
        let f = slot.lock().map(|mut f| f.take()).ok().flatten();
        f.map(|f| f())
    };
    std::thread::scope(|scope| {
        let other = std::thread::Builder::new().spawn_scoped(scope, run);
        let mine = second();
        let theirs = match other {
            Ok(thread) => thread
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic)),
            Err(_) => None,
        };
        let apart = theirs.is_some();
        (theirs.or_else(run).expect("runs once"), mine, apart)
    })
}

/// Runs `f(first, part)` on the two halves of `items` (`first` the index of the part's first
/// item), on two threads from `from` items on, else on this one.
pub fn in_halves<T: Send>(items: &mut [T], from: usize, f: impl Fn(usize, &mut [T]) + Sync) {
    if items.len() < from {
        f(0, items);
        return;
    }
    let mid = items.len() / 2;
    let (low, high) = items.split_at_mut(mid);
    both(|| f(0, low), || f(mid, high));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_run_once_each_and_the_first_on_another_thread() {
        let here = std::thread::current().id();
        let (a, b) = both(
            || (std::thread::current().id(), 1),
            || (std::thread::current().id(), 2),
        );
        assert_eq!((a.1, b.1), (1, 2));
        assert_ne!(a.0, here, "the first runs on a second thread");
        assert_eq!(b.0, here, "the second runs here");
        let (_, _, apart) = both_telling(|| 1, || 2);
        assert!(apart, "and says so");
    }

    #[test]
    fn each_half_is_done_once_with_its_first_index() {
        for (len, from) in [(7, 100), (7, 2), (1, 1), (0, 0)] {
            let mut items: Vec<(usize, usize)> = vec![(0, 0); len];
            in_halves(&mut items, from, |first, part| {
                for (k, item) in part.iter_mut().enumerate() {
                    *item = (item.0 + 1, first + k);
                }
            });
            let want: Vec<(usize, usize)> = (0..len).map(|i| (1, i)).collect();
            assert_eq!(items, want, "{len} items from {from}");
        }
    }

    #[test]
    fn a_panic_on_the_other_thread_reaches_the_caller() {
        let caught = std::panic::catch_unwind(|| both(|| panic!("inside"), || 0));
        assert!(caught.is_err());
    }
}
