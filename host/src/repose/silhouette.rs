//! A pile silhouette: a binary image, row 0 at the top as in a photograph, `true` where the
//! pile is.
//!
//! Both a thresholded photograph and a rasterised simulated pile become a [`Silhouette`];
//! the same cleaning (largest connected blob, holes filled) and the same contour
//! extraction then apply to both, as seed 000 §3.6.1 applies one procedure to every
//! photograph.
//!
//! Topology: the pile is 8-connected and the background 4-connected (the usual dual pair,
//! so a diagonal chain of pile pixels encloses background and no region is counted twice).
//!
//! ```
//! use arachis::repose::Silhouette;
//! // A ring with a hole in the middle, and a stray pixel.
//! let s = Silhouette::from_fn(7, 6, |x, y| {
//!     ((1..=4).contains(&x) && (1..=4).contains(&y) && !(x == 2 && y == 2)) || (x, y) == (6, 0)
//! });
//! let clean = s.largest_blob().filled();
//! assert_eq!(clean.count(), 16);
//! assert!(clean.get(2, 2));
//! assert!(!clean.get(6, 0));
//! ```

/// An image side, for the error when the pile is cut off by the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The left column.
    Left,
    /// The right column.
    Right,
    /// The top row.
    Top,
}

impl std::fmt::Display for Side {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Side::Left => "left",
            Side::Right => "right",
            Side::Top => "top",
        })
    }
}

/// A binary image of a pile seen from the side (pixels; row 0 is the top).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Silhouette {
    width: usize,
    height: usize,
    inside: Vec<bool>,
}

impl Silhouette {
    /// The silhouette with `inside(x, y)` for column x and row y (row 0 at the top).
    pub fn from_fn(width: usize, height: usize, inside: impl Fn(usize, usize) -> bool) -> Self {
        let mut pixels = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                pixels.push(inside(x, y));
            }
        }
        Silhouette {
            width,
            height,
            inside: pixels,
        }
    }

    /// Width (pixels).
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height (pixels).
    pub fn height(&self) -> usize {
        self.height
    }

    /// Whether pixel (column x, row y) is pile.
    pub fn get(&self, x: usize, y: usize) -> bool {
        self.inside[y * self.width + x]
    }

    /// Number of pile pixels.
    pub fn count(&self) -> usize {
        self.inside.iter().filter(|&&p| p).count()
    }

    /// Only the largest 8-connected blob of pile pixels (pods that rolled away, dust and
    /// specks of background noise are dropped). Ties go to the blob met first in row order.
    pub fn largest_blob(&self) -> Silhouette {
        let mut label = vec![0u32; self.inside.len()];
        let mut best = (0usize, 0u32);
        let mut next = 0u32;
        for start in 0..self.inside.len() {
            if self.inside[start] && label[start] == 0 {
                next += 1;
                let size = self.flood(start, &mut label, next, true, true);
                if size > best.0 {
                    best = (size, next);
                }
            }
        }
        Silhouette {
            width: self.width,
            height: self.height,
            inside: label.iter().map(|&l| l != 0 && l == best.1).collect(),
        }
    }

    /// The silhouette with its holes filled: background not 4-connected to the image
    /// border (gaps between pods, shadows inside the pile) becomes pile.
    pub fn filled(&self) -> Silhouette {
        let mut outside = vec![0u32; self.inside.len()];
        for start in self.border_indices() {
            if !self.inside[start] && outside[start] == 0 {
                self.flood(start, &mut outside, 1, false, false);
            }
        }
        Silhouette {
            width: self.width,
            height: self.height,
            inside: outside.iter().map(|&o| o == 0).collect(),
        }
    }

    /// The first of the left, right and top sides that a pile pixel touches, if any.
    /// The bottom may be touched: a photograph may be cropped at the plate.
    pub fn touched_side(&self) -> Option<Side> {
        let (w, h) = (self.width, self.height);
        if (0..h).any(|y| self.get(0, y)) {
            Some(Side::Left)
        } else if (0..h).any(|y| self.get(w - 1, y)) {
            Some(Side::Right)
        } else if (0..w).any(|x| self.get(x, 0)) {
            Some(Side::Top)
        } else {
            None
        }
    }

    fn border_indices(&self) -> Vec<usize> {
        let (w, h) = (self.width, self.height);
        let mut border = Vec::with_capacity(2 * (w + h));
        for x in 0..w {
            border.push(x);
            border.push((h - 1) * w + x);
        }
        for y in 0..h {
            border.push(y * w);
            border.push(y * w + w - 1);
        }
        border
    }

    /// Labels with `mark` every pixel whose value is `value` and that connects to `start`
    /// (8-connected when `diagonal`); returns how many pixels it labelled.
    fn flood(
        &self,
        start: usize,
        label: &mut [u32],
        mark: u32,
        value: bool,
        diagonal: bool,
    ) -> usize {
        let (w, h) = (self.width as isize, self.height as isize);
        let mut stack = vec![start];
        label[start] = mark;
        let mut size = 0;
        while let Some(i) = stack.pop() {
            size += 1;
            let (x, y) = ((i as isize) % w, (i as isize) / w);
            for dy in -1..=1isize {
                for dx in -1..=1isize {
                    let diagonal_step = dx != 0 && dy != 0;
                    if (dx, dy) == (0, 0) || (diagonal_step && !diagonal) {
                        continue;
                    }
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w || ny >= h {
                        continue;
                    }
                    let j = (ny * w + nx) as usize;
                    if self.inside[j] == value && label[j] == 0 {
                        label[j] = mark;
                        stack.push(j);
                    }
                }
            }
        }
        size
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn largest_of_two_blobs_is_kept() {
        let s = Silhouette::from_fn(10, 4, |x, _| !(3..=5).contains(&x));
        let kept = s.largest_blob();
        assert_eq!(kept.count(), 16);
        assert!(kept.get(9, 0) && !kept.get(0, 0));
    }

    #[test]
    fn diagonal_pixels_are_one_blob_and_enclose_background() {
        // A diamond drawn with diagonal steps only: one 8-connected blob enclosing a hole.
        let s = Silhouette::from_fn(5, 5, |x, y| {
            (x as i32 - 2).abs() + (y as i32 - 2).abs() == 2
        });
        assert_eq!(s.largest_blob().count(), 8);
        assert!(s.filled().get(2, 2));
    }

    #[test]
    fn border_sides_are_reported() {
        let inner = Silhouette::from_fn(5, 5, |x, y| (1..4).contains(&x) && y >= 1);
        assert_eq!(inner.touched_side(), None);
        let left = Silhouette::from_fn(5, 5, |x, y| x < 2 && y > 2);
        assert_eq!(left.touched_side(), Some(Side::Left));
        let top = Silhouette::from_fn(5, 5, |x, _| x == 2);
        assert_eq!(top.touched_side(), Some(Side::Top));
    }
}
