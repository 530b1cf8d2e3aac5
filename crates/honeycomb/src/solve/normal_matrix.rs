//! The normal equations `(J^T W J + eps I) dx = -J^T W phi`, assembled straight into a fixed
//! upper-triangular CSC pattern.
//!
//! The pattern and a scatter map (for every row, the value slot of every pair of its variables)
//! are computed once; each iteration only multiplies and adds into the existing value array.

use super::constraint::Constraint;

pub struct NormalMatrix {
    pub n: usize,
    /// Upper triangle, column-compressed: rows of column j are `row_idx[col_ptr[j]..col_ptr[j+1]]`.
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
    diagonal: Vec<usize>,
    /// Per family: the value slot of each (a <= b) variable pair of each row.
    scatter: Vec<Vec<u32>>,
    /// Per family: the variables of each row, row-major.
    row_vars: Vec<Vec<usize>>,
}

impl NormalMatrix {
    pub fn new(n: usize, families: &[Box<dyn Constraint + '_>]) -> NormalMatrix {
        let row_vars: Vec<Vec<usize>> = families
            .iter()
            .map(|c| {
                let k = c.arity();
                let mut vars = vec![0usize; c.num_rows() * k];
                for (row, chunk) in vars.chunks_mut(k).enumerate() {
                    c.row_variables(row, chunk);
                }
                vars
            })
            .collect();
        // The upper-triangular entries column by column, in one flat array: count, place,
        // then sort and deduplicate each column (no per-column allocations).
        let each_pair = |visit: &mut dyn FnMut(usize, usize)| {
            for (c, vars) in families.iter().zip(&row_vars) {
                for chunk in vars.chunks(c.arity()) {
                    for &a in chunk {
                        for &b in chunk {
                            if a < b {
                                visit(a, b);
                            }
                        }
                    }
                }
            }
        };
        let mut start = vec![0usize; n + 1];
        each_pair(&mut |_, b| start[b + 1] += 1);
        for j in 0..n {
            start[j + 1] += start[j] + 1; // + the diagonal
        }
        let mut entries = vec![0usize; start[n]];
        let mut fill: Vec<usize> = start[..n].to_vec();
        for (j, f) in fill.iter_mut().enumerate() {
            entries[*f] = j;
            *f += 1;
        }
        each_pair(&mut |a, b| {
            entries[fill[b]] = a;
            fill[b] += 1;
        });
        drop(fill);
        let mut col_ptr = Vec::with_capacity(n + 1);
        let mut row_idx = Vec::with_capacity(entries.len());
        col_ptr.push(0);
        for j in 0..n {
            let col = &mut entries[start[j]..start[j + 1]];
            col.sort_unstable();
            let first = row_idx.len();
            for &r in col.iter() {
                if row_idx.len() == first || row_idx[row_idx.len() - 1] != r {
                    row_idx.push(r);
                }
            }
            col_ptr.push(row_idx.len());
        }
        drop(entries);
        assert!(
            row_idx.len() < u32::MAX as usize,
            "normal matrix too large for 32-bit slots"
        );
        let slot = |r: usize, c: usize| -> u32 {
            let (r, c) = (r.min(c), r.max(c));
            let range = col_ptr[c]..col_ptr[c + 1];
            let pos = row_idx[range.clone()]
                .binary_search(&r)
                .expect("entry is in the pattern");
            (range.start + pos) as u32
        };
        let diagonal = (0..n).map(|j| slot(j, j) as usize).collect();
        let scatter = families
            .iter()
            .zip(&row_vars)
            .map(|(c, vars)| {
                let k = c.arity();
                let mut map = Vec::with_capacity(c.num_rows() * k * (k + 1) / 2);
                for chunk in vars.chunks(k) {
                    for a in 0..k {
                        for b in a..k {
                            map.push(slot(chunk[a], chunk[b]));
                        }
                    }
                }
                map
            })
            .collect();
        let nnz = row_idx.len();
        NormalMatrix {
            n,
            col_ptr,
            row_idx,
            values: vec![0.0; nnz],
            diagonal,
            scatter,
            row_vars,
        }
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Zeroes the matrix and the right-hand side.
    pub fn clear(&mut self, rhs: &mut [f64]) {
        self.values.fill(0.0);
        rhs.fill(0.0);
    }

    /// Adds family `f`'s weighted rows: `w^2 J^T J` to the matrix, `-w^2 J^T phi` to `rhs`.
    pub fn add_family(
        &mut self,
        f: usize,
        weight: f64,
        residuals: &[f64],
        jacobian: &[f64],
        rhs: &mut [f64],
    ) {
        let k = jacobian.len() / residuals.len().max(1);
        let w2 = weight * weight;
        let map = &self.scatter[f];
        let vars = &self.row_vars[f];
        let npairs = k * (k + 1) / 2;
        for (row, (&phi, j)) in residuals.iter().zip(jacobian.chunks_exact(k)).enumerate() {
            let slots = &map[row * npairs..(row + 1) * npairs];
            let row_vars = &vars[row * k..(row + 1) * k];
            let mut p = 0;
            for a in 0..k {
                let ja = w2 * j[a];
                rhs[row_vars[a]] -= ja * phi;
                for jb in &j[a..k] {
                    self.values[slots[p] as usize] += ja * jb;
                    p += 1;
                }
            }
        }
    }

    pub fn add_diagonal(&mut self, eps: f64) {
        for &d in &self.diagonal {
            self.values[d] += eps;
        }
    }
}
