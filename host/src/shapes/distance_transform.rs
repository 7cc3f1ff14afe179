//! Exact Euclidean distance transform of a voxel occupancy grid: for every inside voxel,
//! the squared distance (in voxel units) to the nearest outside voxel centre.
//!
//! Algorithm: Felzenszwalb & Huttenlocher, "Distance transforms of sampled functions",
//! Theory of Computing 8 (2012): one exact 1-D pass along x, then the lower envelope of
//! parabolas along y and z. Exception to "use a library": no maintained crate offers a 3-D
//! EDT on a plain occupancy array, and the algorithm is a few dozen lines.

use super::voxel_grid::VoxelGrid;

/// Squared distances, in voxel units, from each voxel centre to the nearest outside voxel
/// centre (0 for outside voxels). Every grid line must contain an outside voxel (build the
/// grid with a margin of 1), otherwise inside voxels of that line keep a huge value.
pub fn squared_distance_to_outside(grid: &VoxelGrid, inside: &[bool]) -> Vec<f64> {
    let [nx, ny, nz] = grid.dims;
    // A distance larger than any in the grid, for lines with no outside voxel.
    let far = ((nx + ny + nz) as f64).powi(2) * 4.0;
    let mut dist = vec![0.0; grid.len()];
    // Pass 1 along x: exact 1-D distance to the nearest outside voxel by two sweeps.
    for k in 0..nz {
        for j in 0..ny {
            let row = grid.index(0, j, k);
            let mut last: Option<usize> = None;
            for i in 0..nx {
                if !inside[row + i] {
                    last = Some(i);
                }
                dist[row + i] = last.map_or(far, |p| ((i - p) as f64).powi(2));
            }
            let mut next: Option<usize> = None;
            for i in (0..nx).rev() {
                if !inside[row + i] {
                    next = Some(i);
                }
                if let Some(p) = next {
                    dist[row + i] = dist[row + i].min(((p - i) as f64).powi(2));
                }
            }
        }
    }
    // Passes 2 and 3: lower envelope of parabolas along y, then z.
    let mut line = Vec::new();
    let mut out = Vec::new();
    for (axis_len, stride, outer) in [
        (ny, nx, vec![(nx, 1), (nz, nx * ny)]),
        (nz, nx * ny, vec![(nx, 1), (ny, nx)]),
    ] {
        for a in 0..outer[0].0 {
            for b in 0..outer[1].0 {
                let base = a * outer[0].1 + b * outer[1].1;
                line.clear();
                line.extend((0..axis_len).map(|t| dist[base + t * stride]));
                out.resize(axis_len, 0.0);
                lower_envelope(&line, &mut out);
                for (t, &d) in out.iter().enumerate() {
                    dist[base + t * stride] = d;
                }
            }
        }
    }
    dist
}

/// `out[q] = min_p ((q − p)² + f[p])`, exactly, in O(n).
fn lower_envelope(f: &[f64], out: &mut [f64]) {
    let n = f.len();
    if n == 0 {
        return;
    }
    let mut v = vec![0usize; n];
    let mut z = vec![0.0f64; n + 1];
    let mut k = 0usize;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    for q in 1..n {
        let qf = q as f64;
        let mut s;
        loop {
            let p = v[k] as f64;
            s = ((f[q] + qf * qf) - (f[v[k]] + p * p)) / (2.0 * (qf - p));
            if k > 0 && s <= z[k] {
                k -= 1;
            } else {
                break;
            }
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as f64 - v[k] as f64;
        *o = d * d + f[v[k]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_brute_force_on_a_small_blob() {
        let grid = VoxelGrid {
            min_mm: [0.0; 3],
            spacing_mm: 1.0,
            dims: [9, 8, 7],
        };
        let mut inside = vec![false; grid.len()];
        for k in 1..6 {
            for j in 1..7 {
                for i in 1..8 {
                    // An irregular blob: a box with a notch.
                    inside[grid.index(i, j, k)] = !(i > 4 && j > 3 && k < 3);
                }
            }
        }
        let dist = squared_distance_to_outside(&grid, &inside);
        for k in 0..7 {
            for j in 0..8 {
                for i in 0..9 {
                    let mut best = f64::INFINITY;
                    for kk in 0..7 {
                        for jj in 0..8 {
                            for ii in 0..9 {
                                if !inside[grid.index(ii, jj, kk)] {
                                    let d = (i as f64 - ii as f64).powi(2)
                                        + (j as f64 - jj as f64).powi(2)
                                        + (k as f64 - kk as f64).powi(2);
                                    best = best.min(d);
                                }
                            }
                        }
                    }
                    assert_eq!(dist[grid.index(i, j, k)], best, "voxel {i} {j} {k}");
                }
            }
        }
    }
}
