//! Disjoint sets over `0..n` (union–find with path halving, Tarjan 1975), whose root
//! is always the least member of its set: merging vertices that rounding split keeps
//! the first of them, so outputs do not depend on the order of the unions.

/// A partition of `0..n` into sets, each named by its least member.
pub(crate) struct DisjointSets {
    parent: Vec<usize>,
}

impl DisjointSets {
    /// `n` singletons.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            parent: (0..n).collect(),
        }
    }

    /// The least member of `v`'s set.
    pub(crate) fn find(&mut self, mut v: usize) -> usize {
        while self.parent[v] != v {
            self.parent[v] = self.parent[self.parent[v]];
            v = self.parent[v];
        }
        v
    }

    /// Joins the sets of `a` and `b`.
    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        self.parent[ra.max(rb)] = ra.min(rb);
    }

    /// Every member's root, in member order.
    pub(crate) fn roots(mut self) -> Vec<usize> {
        (0..self.parent.len()).map(|v| self.find(v)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::DisjointSets;

    #[test]
    fn sets_are_named_by_their_least_member() {
        let mut s = DisjointSets::new(6);
        s.union(4, 2);
        s.union(5, 4);
        s.union(3, 1);
        assert_eq!(s.find(5), 2);
        assert_eq!(s.roots(), vec![0, 1, 2, 1, 2, 2]);
    }
}
