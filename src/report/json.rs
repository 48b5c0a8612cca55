//! What the JSON reports share: their canonical key order, an object's `schema_version` and
//! `command` first and every other key in byte order, whatever order a view declares them in.

use serde::ser::SerializeMap;
use serde::Serializer;

/// The keys every JSON report opens with, in this order.
const HEAD: [&str; 2] = ["schema_version", "command"];

/// The view `view` serialised in the canonical key order: its [`HEAD`] keys first, then the
/// other keys of every object in byte order (a number that is not finite is `null`).
pub(crate) fn canonical<T: serde::Serialize, S: Serializer>(
    view: &T,
    s: S,
) -> Result<S::Ok, S::Error> {
    let value = serde_json::to_value(view).map_err(serde::ser::Error::custom)?;
    head_first(&value, s)
}

/// `value` serialised with its [`HEAD`] keys first and its other keys after them in their
/// own order (a value that is not an object as it is).
pub(crate) fn head_first<S: Serializer>(
    value: &serde_json::Value,
    s: S,
) -> Result<S::Ok, S::Error> {
    use serde::Serialize;
    let Some(object) = value.as_object() else {
        return value.serialize(s);
    };
    let mut map = s.serialize_map(Some(object.len()))?;
    for key in HEAD {
        if let Some(v) = object.get(key) {
            map.serialize_entry(key, v)?;
        }
    }
    for (k, v) in object.iter().filter(|(k, _)| !HEAD.contains(&k.as_str())) {
        map.serialize_entry(k, v)?;
    }
    map.end()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn head_keys_come_first_and_nothing_is_lost() {
        let v: serde_json::Value =
            serde_json::from_str(r#"{"a": 1, "command": "x", "z": [2], "schema_version": 3}"#)
                .unwrap();
        let mut out = Vec::new();
        head_first(&v, &mut serde_json::Serializer::new(&mut out)).unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(text, r#"{"schema_version":3,"command":"x","a":1,"z":[2]}"#);
    }
}
