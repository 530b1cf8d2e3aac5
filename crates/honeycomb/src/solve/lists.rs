//! Many short lists in one flat array, built without a vector per list: the sparsity patterns
//! (columns of a matrix, neighbours of an unknown) are made this way.

/// Lists in one flat array: list k is `items[start[k]..start[k + 1]]`.
pub(super) struct Lists<T> {
    start: Vec<usize>,
    items: Vec<T>,
}

impl<T: Copy + Default> Lists<T> {
    /// `count` lists of the items `each` visits as (list, item); `each` runs twice (to count,
    /// then to place), which spares a vector per list.
    pub(super) fn build(count: usize, each: impl Fn(&mut dyn FnMut(usize, T))) -> Lists<T> {
        let mut start = vec![0usize; count + 1];
        each(&mut |k, _| start[k + 1] += 1);
        for k in 0..count {
            start[k + 1] += start[k];
        }
        let mut items = vec![T::default(); start[count]];
        let mut next = start[..count].to_vec();
        each(&mut |k, item| {
            items[next[k]] = item;
            next[k] += 1;
        });
        Lists { start, items }
    }

    pub(super) fn get(&self, k: usize) -> &[T] {
        &self.items[self.start[k]..self.start[k + 1]]
    }
}

impl<T: Copy + Default + Ord> Lists<T> {
    /// Every list sorted and without repeats, compressed: (starts, items).
    pub(super) fn sorted_unique(mut self) -> (Vec<usize>, Vec<T>) {
        let mut start = Vec::with_capacity(self.start.len());
        let mut items = Vec::with_capacity(self.items.len());
        start.push(0);
        for k in 0..self.start.len() - 1 {
            let list = &mut self.items[self.start[k]..self.start[k + 1]];
            list.sort_unstable();
            let first = items.len();
            for &i in list.iter() {
                if items.len() == first || items[items.len() - 1] != i {
                    items.push(i);
                }
            }
            start.push(items.len());
        }
        (start, items)
    }
}
