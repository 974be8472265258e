//! Fields of a JSON scene that the format does not know: they are ignored (so metadata
//! such as `"source"` still works), and listed for the reader to warn about, with the
//! known field it most likely meant.

use super::Scene;
use serde_json::Value;

const SCENE_FIELDS: &[&str] = &["domain", "epsilon", "mode", "sites"];
const METRIC_FIELDS: &[&str] = &["kind", "p", "matrix", "weight", "scale"];

/// The fields a site of `kind` reads, besides `kind` and `id`.
fn site_fields(kind: &str) -> Option<&'static [&'static str]> {
    Some(match kind {
        "point" => &["at", "metric"],
        "circle" => &["center", "radius"],
        "ellipse" => &["center", "semi_axes", "rotation"],
        "segment" => &["from", "to"],
        "arc" => &["center", "radius", "start_angle", "end_angle"],
        "polyline" => &["points"],
        "polygon" => &["rings"],
        "algebraic" => &["equation", "clip"],
        "bezier" => &["control_points", "weights"],
        "bspline" => &["degree", "control_points", "knots", "weights", "closed"],
        "field" | "implicit_field" => &["equation"],
        _ => return None,
    })
}

impl Scene {
    /// One message per field of the JSON scene `value` that the format does not know
    /// (`site 3: unknown field 'radius' (ignored)`), naming the likely intended field
    /// when one is close (`did you mean 'epsilon'?`). Fields of unknown kinds are not
    /// listed: reading refuses the kind itself.
    pub fn unknown_fields(value: &Value) -> Vec<String> {
        let mut out = Vec::new();
        let Some(obj) = value.as_object() else {
            return out;
        };
        unknown_in(obj, SCENE_FIELDS, "", &mut out);
        let sites = obj.get("sites").and_then(Value::as_array);
        for (i, site) in sites.into_iter().flatten().enumerate() {
            let Some(s) = site.as_object() else { continue };
            let Some(known) = s.get("kind").and_then(Value::as_str).and_then(site_fields) else {
                continue;
            };
            let mut all = vec!["kind", "id"];
            all.extend_from_slice(known);
            unknown_in(s, &all, &format!("site {i}: "), &mut out);
            if let Some(m) = s.get("metric").and_then(Value::as_object) {
                unknown_in(m, METRIC_FIELDS, &format!("site {i} metric: "), &mut out);
            }
        }
        out
    }
}

fn unknown_in(
    obj: &serde_json::Map<String, Value>,
    known: &[&str],
    prefix: &str,
    out: &mut Vec<String>,
) {
    for name in obj.keys().filter(|k| !known.contains(&k.as_str())) {
        let shown: String = name.chars().take(40).collect();
        let guess = known
            .iter()
            .map(|k| (edit_distance(name, k), *k))
            .filter(|&(d, k)| d <= 2 && d < k.len())
            .min();
        out.push(match guess {
            Some((_, k)) => {
                format!("{prefix}unknown field '{shown}' (ignored; did you mean '{k}'?)")
            }
            None => format!("{prefix}unknown field '{shown}' (ignored)"),
        });
    }
}

/// The Levenshtein distance, for suggestions (names are short).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().take(64).enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn unknown_fields_are_named_with_the_likely_intended_one() {
        let v = json!({"domain": [0, 0, 1, 1], "epsilion": 0.5, "source": "OSM", "sites": [
            {"kind": "point", "at": [0.5, 0.5], "radius": 1, "metric": {"kind": "power", "wieght": 4}},
            {"kind": "segment", "from": [0, 0], "to": [1, 1], "id": "s"},
            {"kind": "spline", "knots": []}
        ]});
        let w = Scene::unknown_fields(&v);
        assert_eq!(
            w,
            [
                "unknown field 'epsilion' (ignored; did you mean 'epsilon'?)",
                "unknown field 'source' (ignored)",
                "site 0: unknown field 'radius' (ignored)",
                "site 0 metric: unknown field 'wieght' (ignored; did you mean 'weight'?)",
            ]
        );
        // the unknown fields are ignored: only the unknown kind is refused
        assert!(matches!(
            Scene::from_value(&v),
            Err(crate::Error::Site { site: 2, ref field, .. }) if field == "kind"
        ));
    }
}
