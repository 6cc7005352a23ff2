//! Edits to a parsed scene by key path: the mechanism behind `catena convergence` (and, later,
//! parameter sweeps and the Python binding).
//!
//! A key path names a value in the scene's TOML document: tables by name, array entries by index or
//! by `*` (every entry): `dynamic.time_step`, `seabed.stiffness`, `mesh[*].element_length`,
//! `mesh[0].to`. An edit sets the value, scales a number, or removes a key. Every path must exist
//! (a wildcard must match at least one entry), except the last key of a `Set`, which may be new in an
//! existing table: an edit never silently does nothing.

use crate::error::SceneError;

/// What an edit does at its key path.
#[derive(Debug, Clone, PartialEq)]
pub enum EditOp {
    /// Set the value (the key may be new in an existing table).
    Set(toml::Value),
    /// Multiply a number by this factor (integers become floats).
    Scale(f64),
    /// Remove the key if present (the table must exist).
    Remove,
}

/// One edit: a key path and what to do there.
#[derive(Debug, Clone, PartialEq)]
pub struct Edit {
    /// The key path, e.g. `mesh[*].element_length`.
    pub path: String,
    /// The operation.
    pub op: EditOp,
}

impl Edit {
    /// Sets `path` to `value`.
    pub fn set(path: &str, value: impl Into<toml::Value>) -> Self {
        Self {
            path: path.into(),
            op: EditOp::Set(value.into()),
        }
    }

    /// Scales the number(s) at `path` by `factor`.
    pub fn scale(path: &str, factor: f64) -> Self {
        Self {
            path: path.into(),
            op: EditOp::Scale(factor),
        }
    }

    /// Removes `path`.
    pub fn remove(path: &str) -> Self {
        Self {
            path: path.into(),
            op: EditOp::Remove,
        }
    }
}

#[derive(Debug, Clone, PartialEq)]
enum Part {
    Key(String),
    Index(usize),
    All,
}

fn split(path: &str) -> Option<Vec<Part>> {
    let mut parts = Vec::new();
    for seg in path.split('.') {
        let (name, rest) = match seg.find('[') {
            Some(i) => (&seg[..i], &seg[i..]),
            None => (seg, ""),
        };
        if name.is_empty() {
            return None;
        }
        parts.push(Part::Key(name.to_string()));
        let mut rest = rest;
        while !rest.is_empty() {
            let close = rest.find(']')?;
            let inner = rest.get(1..close)?;
            parts.push(if inner == "*" {
                Part::All
            } else {
                Part::Index(inner.parse().ok()?)
            });
            rest = &rest[close + 1..];
            if !(rest.is_empty() || rest.starts_with('[')) {
                return None;
            }
        }
    }
    (!parts.is_empty()).then_some(parts)
}

fn number(v: &toml::Value) -> Option<f64> {
    v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
}

/// Applies `op` at `parts` below `v`; returns how many places were edited, or what was missing.
fn apply_at(v: &mut toml::Value, parts: &[Part], op: &EditOp, done: &str) -> Result<usize, String> {
    let (first, rest) = match parts.split_first() {
        Some(x) => x,
        None => {
            return match op {
                EditOp::Set(x) => {
                    *v = x.clone();
                    Ok(1)
                }
                EditOp::Scale(f) => {
                    let x = number(v).ok_or_else(|| format!("`{done}` is not a number"))?;
                    *v = toml::Value::Float(x * f);
                    Ok(1)
                }
                EditOp::Remove => Err(format!("cannot remove `{done}` itself")),
            }
        }
    };
    match first {
        Part::Key(k) => {
            let t = v
                .as_table_mut()
                .ok_or_else(|| format!("`{done}` is not a table"))?;
            let here = if done.is_empty() {
                k.clone()
            } else {
                format!("{done}.{k}")
            };
            if rest.is_empty() {
                match op {
                    EditOp::Remove => {
                        t.remove(k);
                        return Ok(1);
                    }
                    EditOp::Set(x) => {
                        t.insert(k.clone(), x.clone());
                        return Ok(1);
                    }
                    EditOp::Scale(_) => {}
                }
            }
            let next = t
                .get_mut(k)
                .ok_or_else(|| format!("the scene has no key `{here}`"))?;
            apply_at(next, rest, op, &here)
        }
        Part::Index(i) => {
            let a = v
                .as_array_mut()
                .ok_or_else(|| format!("`{done}` is not an array"))?;
            let n = a.len();
            let next = a
                .get_mut(*i)
                .ok_or_else(|| format!("`{done}` has {n} entries, no [{i}]"))?;
            apply_at(next, rest, op, &format!("{done}[{i}]"))
        }
        Part::All => {
            let a = v
                .as_array_mut()
                .ok_or_else(|| format!("`{done}` is not an array"))?;
            if a.is_empty() {
                return Err(format!("`{done}` has no entries"));
            }
            let mut count = 0;
            for (i, x) in a.iter_mut().enumerate() {
                count += apply_at(x, rest, op, &format!("{done}[{i}]"))?;
            }
            Ok(count)
        }
    }
}

/// Applies the edits to a scene document in order. `file` names the scene in messages.
pub fn apply(file: &str, doc: &mut toml::Table, edits: &[Edit]) -> Result<(), SceneError> {
    for e in edits {
        let parts = split(&e.path).ok_or_else(|| {
            super::invalid(
                file,
                e.path.clone(),
                "a key path such as `dynamic.time_step` or `mesh[*].element_length`",
            )
        })?;
        let mut v = toml::Value::Table(std::mem::take(doc));
        let r = apply_at(&mut v, &parts, &e.op, "");
        if let toml::Value::Table(t) = v {
            *doc = t;
        }
        r.map_err(|why| {
            super::invalid(
                file,
                e.path.clone(),
                format!("a key path that exists ({why})"),
            )
        })?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn doc() -> toml::Table {
        "[dynamic]\ntime_step = 0.05\noutput_interval = 0.1\n[[mesh]]\nto = 10.0\nelement_length = 2\n[[mesh]]\nto = 20.0\nelement_length = 1.0\n"
            .parse()
            .expect("toml")
    }

    #[test]
    fn scales_every_entry_and_sets_and_removes() {
        let mut d = doc();
        apply(
            "f",
            &mut d,
            &[
                Edit::scale("mesh[*].element_length", 0.5),
                Edit::set("dynamic.time_step", 0.025),
                Edit::remove("dynamic.output_interval"),
                Edit::set("mesh[1].to", 30.0),
            ],
        )
        .expect("edits");
        assert_eq!(d["mesh"][0]["element_length"].as_float(), Some(1.0));
        assert_eq!(d["mesh"][1]["element_length"].as_float(), Some(0.5));
        assert_eq!(d["mesh"][1]["to"].as_float(), Some(30.0));
        assert_eq!(d["dynamic"]["time_step"].as_float(), Some(0.025));
        assert!(d["dynamic"].get("output_interval").is_none());
    }

    #[test]
    fn missing_paths_are_errors_naming_the_key() {
        for (path, op) in [
            ("dynamic.duration", EditOp::Scale(2.0)),
            ("statics.tolerance", EditOp::Set(1.0.into())),
            ("mesh[5].to", EditOp::Set(1.0.into())),
            ("dynamic.time_step.x", EditOp::Set(1.0.into())),
            ("mesh[x].to", EditOp::Set(1.0.into())),
            ("", EditOp::Remove),
        ] {
            let mut d = doc();
            let e = apply(
                "case.toml",
                &mut d,
                &[Edit {
                    path: path.into(),
                    op,
                }],
            )
            .expect_err(path);
            let msg = e.to_string();
            assert!(msg.contains("case.toml") && msg.contains(path), "{msg}");
        }
    }
}
