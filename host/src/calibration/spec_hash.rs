//! A stable content hash of one fully specified run: the name of its file in the run cache
//! (issue 4 §4: every finished run is stored under a hash of its full specification).
//!
//! The hash is 64-bit FNV-1a (Fowler–Noll–Vo; offset basis 0xcbf29ce484222325, prime
//! 0x100000001b3) over the canonical JSON of the rig's specification: objects with keys
//! sorted bytewise, no whitespace, numbers as serde_json prints them (shortest round-trip
//! form, the same on every machine). FNV-1a is not cryptographic; it only has to tell
//! different specs apart in a cache of thousands of runs, where a 64-bit hash collides with
//! odds of about n²/2⁶⁵ ≈ 3e-12 at n = 10⁴. The cache compares the whole canonical text
//! before it replays a run, so even a collision cannot mix two runs up.
//!
//! ```
//! use arachis::calibration::spec_hash::fnv1a_64;
//! // Published FNV-1a test vectors.
//! assert_eq!(fnv1a_64(b""), 0xcbf29ce484222325);
//! assert_eq!(fnv1a_64(b"a"), 0xaf63dc4c8601ec8c);
//! ```

use std::fmt;

use serde::{Serialize, Serializer};
use serde_json::Value;

/// FNV-1a 64-bit offset basis.
const FNV_OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
/// FNV-1a 64-bit prime.
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// 64-bit FNV-1a of `bytes`.
pub fn fnv1a_64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(FNV_OFFSET_BASIS, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(FNV_PRIME)
    })
}

/// A run's content hash; prints as 16 lower-case hex digits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SpecHash(pub u64);

impl fmt::Display for SpecHash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:016x}", self.0)
    }
}

/// Serialised as its 16 hex digits, the name of its file in the run cache.
impl Serialize for SpecHash {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

impl SpecHash {
    /// The hash of `spec`'s canonical JSON ([`canonical_json`]).
    pub fn of(spec: &Value) -> Self {
        Self(fnv1a_64(canonical_json(spec).as_bytes()))
    }
}

/// `value` as JSON with object keys sorted and no whitespace, whatever the map type
/// serde_json was built with.
pub fn canonical_json(value: &Value) -> String {
    let mut out = String::new();
    write_canonical(value, &mut out);
    out
}

fn write_canonical(value: &Value, out: &mut String) {
    match value {
        Value::Object(map) => {
            let mut keys: Vec<&String> = map.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::String(k.clone()).to_string());
                out.push(':');
                write_canonical(&map[k], out);
            }
            out.push('}');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_canonical(item, out);
            }
            out.push(']');
        }
        scalar => out.push_str(&scalar.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_json_sorts_keys_at_every_depth() {
        let v = serde_json::json!({"b": 1, "a": {"d": [2.5, {"f": 0, "e": 1}], "c": "x"}});
        assert_eq!(
            canonical_json(&v),
            r#"{"a":{"c":"x","d":[2.5,{"e":1,"f":0}]},"b":1}"#
        );
        assert_eq!(SpecHash::of(&v).to_string().len(), 16);
    }
}
