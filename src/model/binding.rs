//! A saved state belongs to the model it is loaded into: its scene is the instance's own scene
//! (the one its resources hold) with only the declared parameters changed, each to a value its
//! set call takes. A GUID or token in the bytes names the FMU, but the checksum of a
//! serialized state is unkeyed, so the scene itself is compared.

use super::variables::{Access, Value, Variable, VariableTable};
use crate::scene::Scene;

/// Check that `saved` is `exported` with only the parameters of `table` changed: rebuild it
/// from `exported` and the parameter values found in `saved`, and compare. Each value must be
/// one its set call takes (Real: finite; Integer and Enumeration: the declared range and the
/// setter's items); the physical ranges are checked when the model is built, as for values
/// set by the importer. Besides the parameters, only what initialization fills in may differ:
/// `crank.design_speed` (a parameter) and, for a start from rest, the experiment's crank
/// speed 0.
pub fn check_same_model(
    exported: &Scene,
    saved: &Scene,
    table: &VariableTable,
) -> Result<(), String> {
    let mut rebuilt = exported.clone();
    // `saved` with every parameter written by its setter too, so that a value the setter
    // stores in another form (an explicit default) compares equal.
    let mut normalized = saved.clone();
    for v in table.variables() {
        match v.access {
            Access::RealParameter { get, set, .. } => {
                let x = get(saved);
                if !x.is_finite() {
                    return Err(format!(
                        "parameter {} is {x} in the state, allowed a finite value",
                        v.name
                    ));
                }
                set(&mut rebuilt, x);
                set(&mut normalized, x);
            }
            Access::IntegerParameter { get, set } => {
                let n = get(saved);
                check_declared(v, n)?;
                let refused = |e: String| format!("parameter {} is {n} in the state: {e}", v.name);
                set(&mut rebuilt, n).map_err(refused)?;
                set(&mut normalized, n).map_err(refused)?;
            }
            _ => {}
        }
    }
    if normalized.crank.design_speed == 0.0 && normalized.experiment.crank_speed == 0.0 {
        rebuilt.experiment.crank_speed = 0.0;
    }
    if rebuilt == normalized {
        return Ok(());
    }
    Err(format!(
        "this state belongs to another model ({}; a state carries this FMU's scene with only its declared parameters changed)",
        differences(&rebuilt, &normalized)
    ))
}

/// An Integer or Enumeration value within its declared `min`/`max`.
fn check_declared(v: &Variable, n: i32) -> Result<(), String> {
    let low = match v.min {
        Some(Value::Integer(low)) => low,
        _ => i32::MIN,
    };
    let high = match v.max {
        Some(Value::Integer(high)) => high,
        _ => i32::MAX,
    };
    if (low..=high).contains(&n) {
        Ok(())
    } else {
        Err(format!(
            "parameter {} is {n} in the state, allowed an integer in {low}..={high} (the declared range)",
            v.name
        ))
    }
}

/// What differs between this FMU's scene `own` (with the state's parameters) and the state's
/// scene, key by key (at most four, each value shortened).
fn differences(own: &Scene, state: &Scene) -> String {
    let (Ok(own), Ok(state)) = (toml::Value::try_from(own), toml::Value::try_from(state)) else {
        return "its scene differs from this FMU's".to_string();
    };
    let mut found = Vec::new();
    diff("", &own, &state, &mut found);
    let more = found.len().saturating_sub(4);
    found.truncate(4);
    let mut text = found.join("; ");
    if more > 0 {
        text.push_str(&format!("; {more} more"));
    }
    text
}

fn shown(v: Option<&toml::Value>) -> String {
    let text = v.map_or_else(|| "absent".to_string(), |v| v.to_string());
    if text.chars().count() > 60 {
        format!("{}...", text.chars().take(60).collect::<String>())
    } else {
        text
    }
}

fn diff(path: &str, own: &toml::Value, state: &toml::Value, found: &mut Vec<String>) {
    match (own, state) {
        (toml::Value::Table(a), toml::Value::Table(b)) => {
            let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
            keys.sort();
            keys.dedup();
            for key in keys {
                let inner = if path.is_empty() {
                    key.clone()
                } else {
                    format!("{path}.{key}")
                };
                match (a.get(key), b.get(key)) {
                    (Some(x), Some(y)) => diff(&inner, x, y, found),
                    (x, y) => found.push(format!(
                        "{inner} = {} in the state, {} in this FMU's scene",
                        shown(y),
                        shown(x)
                    )),
                }
            }
        }
        (a, b) if a != b => found.push(format!(
            "{path} = {} in the state, {} in this FMU's scene",
            shown(Some(b)),
            shown(Some(a))
        )),
        _ => {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_may_differ_and_nothing_else() {
        let exported = Scene::benchmark();
        let table = VariableTable::new(&exported, 0);
        let mut saved = exported.clone();
        saved.rod.length *= 1.1;
        saved.rod.shear_modulus = Some(saved.rod.youngs_modulus / 2.6);
        check_same_model(&exported, &saved, &table).unwrap();
        saved.name = "other".into();
        saved.solver.step *= 0.5;
        let e = check_same_model(&exported, &saved, &table).unwrap_err();
        assert!(
            e.contains("this state belongs to another model")
                && e.contains("name = \"other\" in the state")
                && e.contains("solver.step"),
            "{e}"
        );
    }
}
