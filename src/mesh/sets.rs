//! Disjoint sets over `0..n`, for labelling connected components.

/// Union–find with path halving; the smaller id is a set's root.
pub(crate) struct DisjointSets(Vec<u32>);

impl DisjointSets {
    /// `n` sets of one element each.
    pub fn new(n: usize) -> DisjointSets {
        DisjointSets((0..n as u32).collect())
    }

    /// The root of `v`'s set.
    pub fn find(&mut self, mut v: u32) -> u32 {
        while self.0[v as usize] != v {
            let up = self.0[self.0[v as usize] as usize];
            self.0[v as usize] = up;
            v = up;
        }
        v
    }

    /// Joins the sets of `a` and `b`; false if they were one already.
    pub fn join(&mut self, a: u32, b: u32) -> bool {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return false;
        }
        self.0[ra.max(rb) as usize] = ra.min(rb);
        true
    }

    /// A label per element, numbering the sets 0, 1, … in order of their smallest
    /// element, and the number of sets.
    pub fn labels(&mut self) -> (Vec<u32>, usize) {
        let n = self.0.len();
        let mut label = vec![u32::MAX; n];
        let mut count = 0;
        for v in 0..n as u32 {
            let r = self.find(v) as usize;
            if label[r] == u32::MAX {
                label[r] = count;
                count += 1;
            }
            label[v as usize] = label[r];
        }
        (label, count as usize)
    }
}
