//! The solver's unknowns, allocated block by block under a name: the honeycomb's first (its
//! vertices, then its wall normals, as [`crate::constraints::Layout`] reads them), then the
//! blocks that families bring of their own. A family is told where its block starts.

use std::ops::Range;

/// A named run of unknowns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    pub name: &'static str,
    pub start: usize,
    pub len: usize,
}

impl Block {
    pub fn range(&self) -> Range<usize> {
        self.start..self.start + self.len
    }

    #[cfg(test)]
    pub fn end(&self) -> usize {
        self.start + self.len
    }
}

/// The unknowns' starting values and the blocks they were allocated in, which follow one
/// another without gaps.
#[derive(Clone, Debug, Default)]
pub struct Unknowns {
    values: Vec<f64>,
    blocks: Vec<Block>,
}

impl Unknowns {
    pub fn new() -> Unknowns {
        Unknowns::default()
    }

    /// Appends a block `name` holding `values`; where it starts is in the returned block.
    pub fn allocate(&mut self, name: &'static str, values: impl IntoIterator<Item = f64>) -> Block {
        let start = self.values.len();
        self.values.extend(values);
        let block = Block {
            name,
            start,
            len: self.values.len() - start,
        };
        self.blocks.push(block);
        block
    }

    pub fn values(&self) -> &[f64] {
        &self.values
    }

    #[cfg(test)]
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// The values and the blocks.
    pub fn into_parts(self) -> (Vec<f64>, Vec<Block>) {
        (self.values, self.blocks)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_follow_one_another() {
        let mut u = Unknowns::new();
        let a = u.allocate("a", [1.0, 2.0, 3.0]);
        let empty = u.allocate("empty", []);
        let b = u.allocate("b", vec![4.0; 2]);
        assert_eq!((a.range(), empty.range(), b.range()), (0..3, 3..3, 3..5));
        assert_eq!(u.blocks(), &[a, empty, b]);
        assert_eq!(u.values(), &[1.0, 2.0, 3.0, 4.0, 4.0]);
    }
}
