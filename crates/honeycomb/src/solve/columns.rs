//! A sparsity pattern built column by column, its entries named in any order: the normal
//! matrix's and the condensed rest's are made this way.
//!
//! Each entry gets a slot at once (the same slot when a row is named again in its column,
//! found by a mark per row rather than a search), and each column is sorted once when it is
//! done; the slots given out are renumbered at the end to match the sorted columns.

pub(super) struct Columns {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// `marked[a] == c + 1`: row a has its entry in the current column c at `slot_of[a]`.
    marked: Vec<usize>,
    slot_of: Vec<usize>,
    /// Slot given out → slot in the sorted columns.
    renumbered: Vec<usize>,
}

/// The finished pattern (column-compressed, rows sorted) and the slots' renumbering.
pub(super) struct Pattern {
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    renumbered: Vec<usize>,
}

impl Columns {
    /// An empty pattern over `rows` rows; columns are added by `entry` and `finish_column`.
    pub fn new(rows: usize) -> Columns {
        Columns {
            col_ptr: vec![0],
            row_idx: Vec::new(),
            marked: vec![0; rows],
            slot_of: vec![0; rows],
            renumbered: Vec::new(),
        }
    }

    /// The (provisional) slot of row `a` in the current column, made if it is new.
    pub fn entry(&mut self, a: usize) -> usize {
        let column = self.col_ptr.len();
        if self.marked[a] != column {
            self.marked[a] = column;
            self.slot_of[a] = self.row_idx.len();
            self.row_idx.push(a);
        }
        self.slot_of[a]
    }

    /// Sorts the current column's rows and starts the next column.
    pub fn finish_column(&mut self) {
        let start = self.col_ptr[self.col_ptr.len() - 1];
        self.row_idx[start..].sort_unstable();
        self.renumbered.resize(self.row_idx.len(), 0);
        for s in start..self.row_idx.len() {
            self.renumbered[self.slot_of[self.row_idx[s]]] = s;
        }
        self.col_ptr.push(self.row_idx.len());
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    pub fn finish(self) -> Pattern {
        Pattern {
            col_ptr: self.col_ptr,
            row_idx: self.row_idx,
            renumbered: self.renumbered,
        }
    }
}

impl Pattern {
    /// The final slot of a slot `entry` gave out.
    pub fn slot(&self, given: usize) -> usize {
        self.renumbered[given]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_named_in_any_order_get_one_slot_each_in_sorted_columns() {
        let mut columns = Columns::new(5);
        let first = [4, 1, 4, 0].map(|a| columns.entry(a));
        columns.finish_column();
        let second = [2, 3, 2].map(|a| columns.entry(a));
        columns.finish_column();
        let p = columns.finish();
        assert_eq!(p.col_ptr, [0, 3, 5]);
        assert_eq!(p.row_idx, [0, 1, 4, 2, 3]);
        assert_eq!(first.map(|s| p.slot(s)), [2, 1, 2, 0]);
        assert_eq!(second.map(|s| p.slot(s)), [3, 4, 3]);
    }
}
