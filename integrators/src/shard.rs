//! Shards: disjoint slices of a render's sample budget, so that several machines can render
//! one image and `footprint merge` can put it together.
//!
//! A render of `spp` passes draws, in pass `k`, camera path `i` from the random stream
//! `(seed, camera, k·npix + i)` and light path `i` from `(seed, light, k·npix + i)`
//! ([`crate::render`]). Shard `i` of `N` renders the passes `k < spp` with `k mod N = i`
//! (strided, not contiguous ranges): every shard's pass set is fixed by `(i, N)` alone, so
//! shard `i/N` of 1024 spp is a subset of shard `i/N` of 2048 spp, the shards' pass counts
//! differ by at most one, and the union of the `N` shards is exactly the pass set `0..spp` of
//! one run with the same seed. Each pass is the same work (one path of each kind per pixel),
//! so either rule balances; strided needs no knowledge of the total to say where a pass goes.

use std::fmt;

/// Which passes of the sample budget a render draws: those `k` with `k mod count = index`.
/// The default, `0/1`, is every pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PassSelection {
    pub index: u32,
    pub count: u32,
}

impl Default for PassSelection {
    fn default() -> Self {
        PassSelection::ALL
    }
}

impl PassSelection {
    /// Every pass: an unsharded render.
    pub const ALL: PassSelection = PassSelection { index: 0, count: 1 };

    /// Shard `index` of `count`; `None` unless `index < count`.
    pub fn shard(index: u32, count: u32) -> Option<Self> {
        (index < count).then_some(PassSelection { index, count })
    }

    pub fn is_all(&self) -> bool {
        self.count == 1
    }

    /// The global pass index of this selection's `j`-th pass.
    pub fn pass(&self, j: u32) -> u32 {
        self.index + j * self.count
    }

    /// How many of the passes `0..spp` this selection draws.
    pub fn passes_of(&self, spp: u32) -> u32 {
        if spp <= self.index {
            0
        } else {
            (spp - self.index).div_ceil(self.count)
        }
    }

    /// Parses `i/N` (zero-based `i`, `0 <= i < N`).
    pub fn parse(s: &str) -> Result<Self, String> {
        let bad = || format!("expected i/N with 0 <= i < N (e.g. 0/4), got '{s}'");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let i: u32 = i.trim().parse().map_err(|_| bad())?;
        let n: u32 = n.trim().parse().map_err(|_| bad())?;
        PassSelection::shard(i, n).ok_or_else(bad)
    }
}

impl fmt::Display for PassSelection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_passes() {
        for spp in [1u32, 7, 16, 33] {
            for n in 1..=5u32 {
                let mut seen = vec![0u32; spp as usize];
                for i in 0..n {
                    let s = PassSelection::shard(i, n).unwrap();
                    for j in 0..s.passes_of(spp) {
                        seen[s.pass(j) as usize] += 1;
                    }
                }
                assert!(seen.iter().all(|&c| c == 1), "spp {spp}, {n} shards");
            }
        }
        assert_eq!(PassSelection::parse("2/4").unwrap().to_string(), "2/4");
        assert!(PassSelection::parse("4/4").is_err());
        assert!(PassSelection::parse("1/0").is_err());
        assert!(PassSelection::parse("x").is_err());
    }
}
