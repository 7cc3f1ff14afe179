//! Names from input that become parts of file names: a study's name and its mode names
//! (`calibration-NAME-MODE/`), a diagnosis study's name. Such a name must stay one plain
//! component of a path inside the output folder, so a study cannot make a command write
//! elsewhere (`name = "x/../../../escaped"` once wrote three folders up).
//!
//! ```
//! use arachis::io::file_name::check_name_component;
//! assert!(check_name_component("peanut-pods-saline").is_ok());
//! assert!(check_name_component("x/../../escaped").is_err());
//! assert!(check_name_component("..").is_err());
//! ```

/// Longest accepted name, in characters: names are labels, and file systems cap a path
/// component at 255 bytes.
pub const MAX_NAME_CHARS: usize = 100;

/// `Ok` when `name` can be one component of a file name: not empty, at most
/// [`MAX_NAME_CHARS`] characters, no path separator (`/`, `\`), no control character, and
/// not starting with `.` (which also rules out `.` and `..`, and hidden files). The error
/// says which rule failed.
pub fn check_name_component(name: &str) -> Result<(), String> {
    let chars = name.chars().count();
    if name.trim().is_empty() {
        return Err("the name is empty".into());
    }
    if chars > MAX_NAME_CHARS {
        return Err(format!(
            "the name is {chars} characters long; at most {MAX_NAME_CHARS} are accepted"
        ));
    }
    if let Some(c) = name
        .chars()
        .find(|c| matches!(c, '/' | '\\') || c.is_control())
    {
        return Err(format!(
            "the name becomes part of a file name and may not hold {c:?} (a path separator or \
             control character)"
        ));
    }
    if name.starts_with('.') {
        return Err("the name becomes part of a file name and may not start with '.'".into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plain_names_pass_and_every_escape_is_refused() {
        for ok in ["seed 000", "peanut_pods-saline.v2", "α-β"] {
            assert!(check_name_component(ok).is_ok(), "{ok}");
        }
        for bad in [
            "",
            "  ",
            "x/../../escaped",
            "a\\b",
            "..",
            ".hidden",
            "tab\there",
            &"n".repeat(MAX_NAME_CHARS + 1),
        ] {
            assert!(check_name_component(bad).is_err(), "{bad:?}");
        }
    }
}
