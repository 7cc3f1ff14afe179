//! Otsu's threshold: the grey level that best splits an 8-bit image into two classes.
//!
//! Seed 000 §3.6.1 greys and binarises the pile photograph before extracting the contour;
//! it does not name the threshold rule, and Otsu's (N. Otsu, "A threshold selection method
//! from gray-level histograms", IEEE Trans. SMC 9(1), 1979) is Matlab's `graythresh`, the
//! usual choice. Pixels at or below the threshold t form class 0, the rest class 1; t
//! maximises the between-class variance
//!
//! σ_B²(t) = ω₀(t) ω₁(t) (μ₀(t) − μ₁(t))²,
//!
//! with ωᵢ the class fractions and μᵢ the class mean grey levels.
//!
//! Written here rather than taken from `imageproc` (an exception to "use well-kept
//! libraries"): it is twenty lines over a 256-bin histogram, and `imageproc` would pull in
//! a large dependency tree for this one function.
//!
//! ```
//! use arachis::repose::otsu::{grey_histogram, otsu_threshold};
//! let pixels = [10u8, 12, 11, 200, 201, 199];
//! let t = otsu_threshold(&grey_histogram(&pixels)).unwrap();
//! assert!((12..199).contains(&t));
//! ```

/// Number of grey levels of an 8-bit image.
pub const GREY_LEVELS: usize = 256;

/// Counts of each grey level 0–255.
pub fn grey_histogram(pixels: &[u8]) -> [u64; GREY_LEVELS] {
    let mut histogram = [0u64; GREY_LEVELS];
    for &p in pixels {
        histogram[usize::from(p)] += 1;
    }
    histogram
}

/// Otsu's threshold t (grey level, 0–255): class 0 is `≤ t`, class 1 is `> t`.
///
/// When several thresholds give the same largest σ_B² (an empty stretch of grey levels
/// between two modes), the middle of that stretch is returned, so a clean two-level image
/// splits half-way between its levels. `None` when the image holds a single grey level.
pub fn otsu_threshold(histogram: &[u64; GREY_LEVELS]) -> Option<u8> {
    let total: f64 = histogram.iter().map(|&c| c as f64).sum();
    let grand_sum: f64 = histogram
        .iter()
        .enumerate()
        .map(|(level, &c)| level as f64 * c as f64)
        .sum();
    let mut weight_0 = 0.0;
    let mut sum_0 = 0.0;
    let mut variances = [0.0f64; GREY_LEVELS];
    for (level, &count) in histogram.iter().enumerate() {
        weight_0 += count as f64;
        sum_0 += level as f64 * count as f64;
        let weight_1 = total - weight_0;
        if weight_0 > 0.0 && weight_1 > 0.0 {
            let mean_0 = sum_0 / weight_0;
            let mean_1 = (grand_sum - sum_0) / weight_1;
            variances[level] = weight_0 * weight_1 * (mean_0 - mean_1).powi(2);
        }
    }
    let best = variances.iter().copied().fold(0.0, f64::max);
    if best <= 0.0 {
        return None;
    }
    // Equal maxima come from identical class contents, so compare exactly.
    let first = variances.iter().position(|&v| v == best)?;
    let run = variances[first..]
        .iter()
        .take_while(|&&v| v == best)
        .count();
    u8::try_from(first + (run - 1) / 2).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_level_image_splits_half_way() {
        let mut pixels = vec![40u8; 300];
        pixels.extend(vec![220u8; 700]);
        let t = otsu_threshold(&grey_histogram(&pixels)).unwrap();
        // Every t in 40..220 separates the two levels equally well; the middle is 129.
        assert_eq!(t, 129);
    }

    #[test]
    fn uniform_image_has_no_threshold() {
        assert_eq!(otsu_threshold(&grey_histogram(&[77u8; 50])), None);
        assert_eq!(otsu_threshold(&grey_histogram(&[])), None);
    }

    #[test]
    fn noisy_modes_split_between_them() {
        // Two triangular modes around 60 and 180, unequal sizes.
        let mut pixels = Vec::new();
        for d in 0..20u8 {
            for _ in 0..(20 - d) {
                pixels.extend([60 + d, 60 - d]);
                pixels.extend([180 + d, 180 - d, 180 + d, 180 - d]);
            }
        }
        let t = otsu_threshold(&grey_histogram(&pixels)).unwrap();
        assert!((80..160).contains(&t), "t = {t}");
    }
}
