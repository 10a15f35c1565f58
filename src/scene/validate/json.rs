//! JSON text → a body type, with serde's errors turned into [`ValidationError`]s that
//! name the field (`object.materials[0].albedo`, `samples[3].phi_deg`) and say "invalid
//! JSON" only for broken syntax.
//!
//! One mapping serves every body; the light-curve request words two cases more closely
//! than the others do (see [`Wording`]), and each keeps the answers it always gave.

use super::ValidationError;
use crate::scene::request::Request;
use serde::de::DeserializeOwned;

/// Parses request JSON, turning serde's errors into field-naming ones.
pub fn parse_request(text: &str) -> Result<Request, ValidationError> {
    parse(text, &REQUEST)
}

/// Parses any JSON body type with the same field-naming errors as [`parse_request`]
/// (e.g. `samples[3].phi_deg: invalid type: string "x", expected f64`).
pub fn parse_json<T: DeserializeOwned>(text: &str) -> Result<T, ValidationError> {
    parse(text, &OTHER_BODY)
}

/// Where the wording of one body type's errors differs from another's.
struct Wording {
    /// What the body is called in "invalid JSON: data after the …".
    body: &'static str,
    /// serde's "trailing characters" at a field is reported as a fixed-length array
    /// given too many elements.
    fixed_arrays: bool,
}

/// The light-curve request (`POST /v1/lightcurves`, jobs, the command line).
const REQUEST: Wording = Wording {
    body: "request",
    fixed_arrays: true,
};

/// Any other body (the BRDF fit).
const OTHER_BODY: Wording = Wording {
    body: "body",
    fixed_arrays: false,
};

fn parse<T: DeserializeOwned>(text: &str, wording: &Wording) -> Result<T, ValidationError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let value: T =
        serde_path_to_error::deserialize(&mut *de).map_err(|e| field_error(e, wording))?;
    // one body per request: anything after it but whitespace is refused, not ignored
    de.end().map_err(|e| {
        ValidationError::new(
            "",
            format!("invalid JSON: data after the {} ({e})", wording.body),
        )
    })?;
    Ok(value)
}

/// serde's error at a path → the field it names and a message without serde's position.
fn field_error(
    e: serde_path_to_error::Error<serde_json::Error>,
    wording: &Wording,
) -> ValidationError {
    let mut field = e.path().to_string();
    if field == "." {
        field.clear();
    }
    let inner = e.into_inner();
    let message = inner.to_string();
    // Name the unknown, missing or repeated field itself; serde_path_to_error's path
    // may already end with it (a missing one's path is the object that lacks it: a
    // request without `object` would otherwise name no field at all).
    let named_in = message
        .strip_prefix("unknown field `")
        .or_else(|| message.strip_prefix("missing field `"))
        .or_else(|| message.strip_prefix("duplicate field `"));
    if let Some(rest) = named_in {
        if let Some(name) = rest.split('`').next() {
            let named = field == name || field.ends_with(&format!(".{name}"));
            if !named {
                field = if field.is_empty() {
                    name.to_string()
                } else {
                    format!("{field}.{name}")
                };
            }
        }
    }
    // Strip serde's "at line L column C" suffix from the field-level message but
    // keep it for syntax errors, where there is no field to name.
    // serde reads a fixed-length array ([f64; 3]) and then expects its end: a longer
    // one reports "trailing characters" at the field, which is a wrong value (422),
    // not broken JSON
    let message = if wording.fixed_arrays
        && message.starts_with("trailing characters")
        && !field.is_empty()
    {
        "more elements than this fixed-length array takes".to_string()
    } else if inner.is_syntax() || inner.is_eof() {
        format!("invalid JSON: {message}")
    } else {
        match message.rfind(" at line ") {
            Some(i) => message[..i].to_string(),
            None => message,
        }
    };
    // a body of the wrong type altogether (`true`, `[]`): the field is the body, as the
    // HTTP layer names it for an empty or oversized one
    if field.is_empty() && inner.is_data() {
        field = "body".to_string();
    }
    ValidationError { field, message }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::test_fixtures::minimal_request;
    use serde_json::json;

    #[test]
    fn an_unknown_field_is_named_with_its_path() {
        let mut v = minimal_request();
        v["object"]["colour"] = json!("red");
        let e = parse_request(&v.to_string()).unwrap_err();
        assert_eq!(e.field, "object.colour");
        assert!(e.message.starts_with("unknown field `colour`"), "{e}");
        assert!(!e.message.contains(" at line "), "{e}");
    }

    #[test]
    fn a_body_that_is_not_an_object_names_the_body() {
        let e = parse_request("true").unwrap_err();
        assert_eq!(e.field, "body", "{e}");
        assert!(e.message.starts_with("invalid type: boolean `true`"), "{e}");
    }

    #[test]
    fn a_missing_field_is_named_at_the_top_and_inside() {
        let e = parse_request("{}").unwrap_err();
        assert_eq!(e.field, "object");
        assert!(e.message.starts_with("missing field `object`"), "{e}");
        let mut v = minimal_request();
        v["object"].as_object_mut().unwrap().remove("materials");
        let e = parse_request(&v.to_string()).unwrap_err();
        assert_eq!(e.field, "object.materials", "{e}");
    }

    #[test]
    fn a_longer_fixed_array_is_a_wrong_value_not_broken_json() {
        let mut v = minimal_request();
        v["epochs"][0]["sun"] = json!([0.0, 0.0, 1.0, 2.0]);
        let e = parse_request(&v.to_string()).unwrap_err();
        assert_eq!(
            e,
            ValidationError::new(
                "epochs[0].sun",
                "more elements than this fixed-length array takes"
            )
        );
    }

    #[test]
    fn every_body_names_a_repeated_field() {
        let text = minimal_request().to_string();
        let twice = format!("{{\"tolerance\": 0.1, \"tolerance\": 0.1, {}", &text[1..]);
        let e = parse_request(&twice).unwrap_err();
        assert_eq!(e.field, "tolerance");
        assert!(e.message.starts_with("duplicate field `tolerance`"), "{e}");

        #[derive(Debug, serde::Deserialize)]
        #[allow(dead_code)]
        struct Body {
            a: f64,
        }
        let e = parse_json::<Body>(r#"{"a": 1, "a": 2}"#).unwrap_err();
        assert_eq!(e.field, "a");
        assert!(e.message.starts_with("duplicate field `a`"), "{e}");
    }

    #[test]
    fn broken_json_and_data_after_the_body_say_invalid_json() {
        let e = parse_request("{").unwrap_err();
        assert!(e.message.starts_with("invalid JSON: EOF"), "{e}");
        let text = minimal_request().to_string();
        let e = parse_request(&format!("{text} {{}}")).unwrap_err();
        assert!(
            e.message
                .starts_with("invalid JSON: data after the request ("),
            "{e}"
        );
        let e = parse_json::<serde_json::Value>("{} 1").unwrap_err();
        assert!(
            e.message.starts_with("invalid JSON: data after the body ("),
            "{e}"
        );
    }
}
