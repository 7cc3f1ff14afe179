//! Duplicate keys in JSON input. `serde_json` keeps the last of two equal keys of an object
//! without a word, so a fit file with `"response"` twice read as whichever came last. This
//! walks a document with serde's own deserializer (no parser of ours) and refuses the first
//! object key that repeats, naming it and the line it repeats on.
//!
//! ```
//! use arachis::io::json_keys::check_unique_keys;
//! assert!(check_unique_keys(r#"{"a": 1, "b": {"a": 2}}"#).is_ok());
//! let e = check_unique_keys("{\"a\": 1,\n \"a\": 2}").unwrap_err();
//! assert!(e.contains("'a'") && e.contains("line 2"), "{e}");
//! ```

use std::collections::BTreeSet;
use std::fmt;

use serde::de::{self, DeserializeSeed, Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};

/// `Ok` when no object of the JSON `text` has a key twice; else which key, and where. A text
/// that is not JSON is `Ok` here: the caller's parser reports that with its own position.
pub fn check_unique_keys(text: &str) -> Result<(), String> {
    let mut de = serde_json::Deserializer::from_str(text);
    match Unique.deserialize(&mut de) {
        Ok(()) => Ok(()),
        Err(e) if e.is_data() => Err(format!("{e}")),
        Err(_) => Ok(()),
    }
}

/// A value of any shape whose objects are checked for repeated keys.
#[derive(Clone, Copy)]
struct Unique;

impl<'de> DeserializeSeed<'de> for Unique {
    type Value = ();
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Unique {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("any JSON value")
    }

    fn visit_bool<E>(self, _: bool) -> Result<(), E> {
        Ok(())
    }
    fn visit_i64<E>(self, _: i64) -> Result<(), E> {
        Ok(())
    }
    fn visit_u64<E>(self, _: u64) -> Result<(), E> {
        Ok(())
    }
    fn visit_f64<E>(self, _: f64) -> Result<(), E> {
        Ok(())
    }
    fn visit_str<E>(self, _: &str) -> Result<(), E> {
        Ok(())
    }
    fn visit_unit<E>(self) -> Result<(), E> {
        Ok(())
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        while seq.next_element_seed(Unique)?.is_some() {}
        Ok(())
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        let mut seen = BTreeSet::new();
        while let Some(key) = map.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                // The error is positioned by serde_json: after the repeated key.
                let _ = map.next_value::<IgnoredAny>();
                return Err(de::Error::custom(format_args!(
                    "the key '{key}' appears twice in one object"
                )));
            }
            map.next_value_seed(Unique)?;
        }
        Ok(())
    }
}
