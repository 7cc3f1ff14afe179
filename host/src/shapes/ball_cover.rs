//! Bookkeeping for the greedy sphere placement: which voxels of a grid are covered, and how
//! many voxels of a lattice ball are not yet covered.
//!
//! A ball of radius r (voxel units) around a voxel is the set of lattice offsets with
//! di² + dj² + dk² ≤ r²; it is stored as runs along x (one per (dj, dk)), and each x-row of
//! the grid keeps a prefix sum of covered voxels, so counting a ball's uncovered voxels
//! costs one subtraction per run instead of one test per voxel.

use super::voxel_grid::VoxelGrid;

/// One x-run of a ball: rows offset (dj, dk), x offsets −half_width..=half_width.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Run {
    /// Offset along y, voxels.
    pub dj: i64,
    /// Offset along z, voxels.
    pub dk: i64,
    /// Half-width along x, voxels.
    pub half_width: i64,
}

/// The x-runs of the lattice ball of radius `radius_vox` (voxel units).
pub fn ball_runs(radius_vox: f64) -> Vec<Run> {
    let r2 = radius_vox * radius_vox;
    let reach = radius_vox.floor().max(0.0) as i64;
    let mut runs = Vec::new();
    for dk in -reach..=reach {
        for dj in -reach..=reach {
            let rest = r2 - (dj * dj + dk * dk) as f64;
            if rest < 0.0 {
                continue;
            }
            // Largest w with w² ≤ rest, corrected for rounding of the square root.
            let mut w = rest.sqrt().floor() as i64;
            while ((w + 1) * (w + 1)) as f64 <= rest {
                w += 1;
            }
            while w > 0 && (w * w) as f64 > rest {
                w -= 1;
            }
            runs.push(Run {
                dj,
                dk,
                half_width: w,
            });
        }
    }
    runs
}

/// Number of voxels in a ball given by its runs.
pub fn ball_volume(runs: &[Run]) -> usize {
    runs.iter().map(|r| (2 * r.half_width + 1) as usize).sum()
}

/// Covered flags of a grid with per-row prefix sums.
pub struct CoveredSet {
    dims: [usize; 3],
    covered: Vec<bool>,
    /// Per row (j, k): nx + 1 prefix counts of covered voxels.
    prefix: Vec<u32>,
    count: usize,
}

impl CoveredSet {
    /// Nothing covered yet.
    pub fn new(grid: &VoxelGrid) -> Self {
        let [nx, ny, nz] = grid.dims;
        CoveredSet {
            dims: grid.dims,
            covered: vec![false; grid.len()],
            prefix: vec![0; (nx + 1) * ny * nz],
            count: 0,
        }
    }

    /// Voxels covered so far.
    pub fn count(&self) -> usize {
        self.count
    }

    fn row(&self, j: i64, k: i64) -> usize {
        j as usize + self.dims[1] * k as usize
    }

    /// Uncovered voxels of the ball `runs` around voxel (i, j, k). The ball must lie inside
    /// the grid.
    pub fn uncovered_in(&self, (i, j, k): (i64, i64, i64), runs: &[Run]) -> usize {
        let stride = self.dims[0] + 1;
        runs.iter()
            .map(|r| {
                let base = self.row(j + r.dj, k + r.dk) * stride;
                let (lo, hi) = ((i - r.half_width) as usize, (i + r.half_width + 1) as usize);
                let covered = (self.prefix[base + hi] - self.prefix[base + lo]) as usize;
                (2 * r.half_width + 1) as usize - covered
            })
            .sum()
    }

    /// Covers the ball `runs` around voxel (i, j, k).
    pub fn cover(&mut self, (i, j, k): (i64, i64, i64), runs: &[Run]) {
        let nx = self.dims[0];
        for r in runs {
            let row = self.row(j + r.dj, k + r.dk);
            let first = row * nx;
            for x in (i - r.half_width) as usize..=(i + r.half_width) as usize {
                if !self.covered[first + x] {
                    self.covered[first + x] = true;
                    self.count += 1;
                }
            }
            let base = row * (nx + 1);
            for x in 0..nx {
                self.prefix[base + x + 1] =
                    self.prefix[base + x] + u32::from(self.covered[first + x]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_hold_exactly_the_lattice_ball() {
        for r in [0.5, 1.0, 2.3, 4.0, 7.7] {
            let reach = r as i64 + 1;
            let mut brute = 0;
            for dk in -reach..=reach {
                for dj in -reach..=reach {
                    for di in -reach..=reach {
                        if ((di * di + dj * dj + dk * dk) as f64) <= r * r {
                            brute += 1;
                        }
                    }
                }
            }
            assert_eq!(ball_volume(&ball_runs(r)), brute, "radius {r}");
        }
    }

    #[test]
    fn uncovered_count_falls_after_covering() {
        let grid = VoxelGrid {
            min_mm: [0.0; 3],
            spacing_mm: 1.0,
            dims: [12, 12, 12],
        };
        let mut set = CoveredSet::new(&grid);
        let runs = ball_runs(3.0);
        let n = ball_volume(&runs);
        assert_eq!(set.uncovered_in((5, 5, 5), &runs), n);
        set.cover((5, 5, 5), &runs);
        assert_eq!(set.count(), n);
        assert_eq!(set.uncovered_in((5, 5, 5), &runs), 0);
        // A ball shifted by one voxel along x gains one new cap of voxels.
        let shifted = set.uncovered_in((6, 5, 5), &runs);
        assert!(shifted > 0 && shifted < n);
    }
}
