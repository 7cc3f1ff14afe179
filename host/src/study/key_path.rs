//! Key paths into a TOML document, printed the way a user would write them.
//!
//! A path is a list of table keys and array positions. Keys made only of ASCII letters,
//! digits and `_` print bare; any other key prints quoted, so
//! `parameters."pod-pod.static_friction".low` can be pasted back into a TOML file.
//! Array positions print 1-based, as a reader counts `[[measurements]]` blocks:
//! `measurements[1]` is the first block.
//!
//! ```
//! use arachis::study::KeyPath;
//! let p = KeyPath::root().key("parameters").key("pod-pod.static_friction").key("low");
//! assert_eq!(p.to_string(), r#"parameters."pod-pod.static_friction".low"#);
//! assert_eq!(KeyPath::root().key("measurements").index(0).to_string(), "measurements[1]");
//! ```

use std::fmt;

/// One step of a [`KeyPath`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Segment {
    /// A table key.
    Key(String),
    /// A 0-based array position (printed 1-based).
    Index(usize),
}

/// A path from the document root to a key or array element.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct KeyPath(pub Vec<Segment>);

impl KeyPath {
    /// The document root (prints as an empty string).
    pub fn root() -> Self {
        Self(Vec::new())
    }

    /// This path extended by a table key.
    pub fn key(&self, key: &str) -> Self {
        let mut next = self.clone();
        next.0.push(Segment::Key(key.to_owned()));
        next
    }

    /// This path extended by a 0-based array position.
    pub fn index(&self, index: usize) -> Self {
        let mut next = self.clone();
        next.0.push(Segment::Index(index));
        next
    }

    /// True for the document root.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// True when TOML accepts `key` unquoted and it has no `-` (we quote `pod-pod` too, so pair
/// names read the same in every message).
fn prints_bare(key: &str) -> bool {
    !key.is_empty() && key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

impl fmt::Display for KeyPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, segment) in self.0.iter().enumerate() {
            match segment {
                Segment::Key(k) => {
                    if i > 0 {
                        f.write_str(".")?;
                    }
                    if prints_bare(k) {
                        f.write_str(k)?;
                    } else {
                        write!(f, "\"{}\"", k.replace('\\', "\\\\").replace('"', "\\\""))?;
                    }
                }
                Segment::Index(n) => write!(f, "[{}]", n + 1)?,
            }
        }
        Ok(())
    }
}
