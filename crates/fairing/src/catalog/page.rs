//! A method's page of the user guide, rendered as Markdown from its catalogue entry: name,
//! kind, paper, summary, what it refuses, and the settings table (name, type, default,
//! range, meaning) read from the settings' JSON Schema — so the page cannot drift from the
//! code. `docs/methods/<kind>/<name>.md` holds hand-written prose above
//! [`GENERATED_MARKER`] and this text below it; the fairing crate's test `method_pages`
//! compares the two and rewrites the generated part with `FAIR_BLESS=1`.

use serde_json::Value;

use super::schema::{self, ParameterInfo};
use super::{Catalog, MethodEntry, MethodKind};

/// The line after which a method page is generated from the catalogue (hand-written prose
/// may stand above it).
pub const GENERATED_MARKER: &str =
    "<!-- Generated from the catalogue below this line (fairing::catalog::MethodEntry::page): \
     edit the settings' doc comments, then run FAIR_BLESS=1 cargo test -p fairing --test fairing method_pages -->";

impl MethodEntry {
    /// The page's file name under `docs/methods/`: `curve/two-phase.md`,
    /// `surface/zhang-cheng.md` (a curve and a surface method may share a name).
    pub fn page_path(&self) -> String {
        format!("{}/{}.md", self.info.kind.name(), self.info.name)
    }

    /// The generated part of the method's page (what follows [`GENERATED_MARKER`]).
    pub fn page(&self) -> String {
        let info = &self.info;
        let command = match info.kind {
            MethodKind::Curve => "fair curve",
            MethodKind::Surface => "fair surface",
        };
        let mut page = String::new();
        page.push_str("\n\n## Catalogue entry\n\n| | |\n|---|---|\n");
        page.push_str(&format!("| name | `{}` |\n", info.name));
        page.push_str(&format!("| kind | {} |\n", info.kind.name()));
        if !info.paper.is_empty() {
            page.push_str(&format!("| paper | {} |\n", cell(&info.paper)));
        }
        page.push_str(&format!("| summary | {} |\n", cell(&info.summary)));
        page.push_str(&format!(
            "| bad points (`--points`) | {} |\n",
            if self.takes_bad_points() {
                "taken: the named points are the ones it replaces"
            } else {
                "refused"
            }
        ));
        page.push_str(&format!(
            "| run | `{command} FILE --method {} --set NAME=VALUE` |\n",
            info.name
        ));
        let pinned: Vec<String> = self
            .pinned
            .iter()
            .filter_map(|name| {
                let value = self.defaults.get(name)?;
                Some(format!("`{name}` = `{}`", schema::value_to_text(value)))
            })
            .collect();
        if !pinned.is_empty() {
            page.push_str(&format!("| fixed by this preset | {} |\n", pinned.join(", ")));
        }
        page.push_str("\n## Settings\n\n");
        if self.parameters.is_empty() {
            page.push_str("None.\n");
            return page;
        }
        page.push_str(&format!(
            "Each is given as `--set NAME=VALUE`, in a config file (top level, a `[{}]` table, or a \
             `[[stage]]` with `method = \"{}\"`), or as `params` of the Python package and of \
             `fair serve`'s API. Ranges are those the schema states; `fair` refuses any other value \
             a method cannot use, naming it.\n\n",
            info.name, info.name
        ));
        page.push_str("| name | type | default | range | meaning |\n|---|---|---|---|---|\n");
        for parameter in &self.parameters {
            page.push_str(&self.row(parameter));
        }
        page
    }

    fn row(&self, parameter: &ParameterInfo) -> String {
        let root = &self.schema;
        let property = &parameter.schema;
        let (kind, range) = type_and_range(property, root);
        let mut doc = doc_text(property, root);
        let choices = choice_docs(property, root);
        if !choices.is_empty() {
            doc.push_str(&format!(" Values: {}.", strip_doc_links(&choices.join("; "))));
        }
        let default = if parameter.default.is_empty() {
            "(empty)".to_owned()
        } else {
            format!("`{}`", parameter.default.replace('|', "\\|"))
        };
        format!(
            "| `{}` | {} | {} | {} | {} |\n",
            parameter.name,
            kind,
            default,
            range,
            cell(&doc)
        )
    }
}

impl Catalog {
    /// Every method's page: its path under `docs/methods/` and its generated part, in
    /// registration order (curves, then surfaces).
    pub fn pages(&self) -> Vec<(String, String)> {
        [MethodKind::Curve, MethodKind::Surface]
            .into_iter()
            .flat_map(|kind| self.methods(kind))
            .map(|m| (m.page_path(), m.page()))
            .collect()
    }
}

/// `schema` with a `$ref` into the root's `$defs` followed (one level is all settings use).
fn resolved<'a>(schema: &'a Value, root: &'a Value) -> &'a Value {
    let Some(reference) = schema.get("$ref").and_then(Value::as_str) else {
        return schema;
    };
    let name = reference.rsplit('/').next().unwrap_or_default();
    root.get("$defs")
        .or_else(|| root.get("definitions"))
        .and_then(|d| d.get(name))
        .unwrap_or(schema)
}

/// The string values a property takes, with their doc where the schema has one.
fn choices(schema: &Value, root: &Value) -> Vec<(String, Option<String>)> {
    let schema = resolved(schema, root);
    let mut out = Vec::new();
    if let Some(Value::Array(values)) = schema.get("enum") {
        out.extend(
            values
                .iter()
                .filter_map(Value::as_str)
                .map(|v| (v.to_owned(), None)),
        );
    }
    if let Some(Value::String(value)) = schema.get("const") {
        out.push((value.clone(), description(schema)));
    }
    for key in ["oneOf", "anyOf"] {
        if let Some(Value::Array(branches)) = schema.get(key) {
            for branch in branches {
                out.extend(choices(branch, root));
            }
        }
    }
    out
}

/// The value docs of a property's choices (`` `a`: meaning ``), where any has one.
fn choice_docs(schema: &Value, root: &Value) -> Vec<String> {
    let all = choices(schema, root);
    if all.iter().all(|(_, doc)| doc.is_none()) {
        return Vec::new();
    }
    all.into_iter()
        .map(|(value, doc)| match doc {
            Some(d) => format!("`{value}`: {}", d.trim_end_matches('.')),
            None => format!("`{value}`"),
        })
        .collect()
}

/// The type column (the JSON types and words a value may be) and the range column (bounds
/// the schema states, or the words a choice takes).
fn type_and_range(schema: &Value, root: &Value) -> (String, String) {
    let types = schema::accepted_types(schema, root);
    let words: Vec<String> = choices(schema, root).into_iter().map(|(v, _)| v).collect();
    let numeric = types.contains("number") || types.contains("integer");
    let base = if types.contains("number") {
        "number"
    } else if types.contains("integer") {
        "integer"
    } else if types.contains("boolean") {
        "boolean"
    } else if types.contains("array") {
        "list"
    } else if !words.is_empty() {
        "choice"
    } else {
        "text"
    };
    let kind = if numeric && !words.is_empty() {
        let quoted: Vec<String> = words.iter().map(|w| format!("`{w}`")).collect();
        format!("{base} or {}", quoted.join(" or "))
    } else if types.contains("null") {
        format!("{base} or none")
    } else {
        base.to_owned()
    };
    let bounds = schema::NumberRange::of(schema, root).and_then(|r| r.bounds());
    let range = if let Some(bounds) = bounds {
        bounds
    } else if base == "choice" {
        words
            .iter()
            .map(|w| format!("`{w}`"))
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        "—".to_owned()
    };
    (kind, range)
}

/// A schema's own doc: its title and description, as one paragraph.
fn description(schema: &Value) -> Option<String> {
    let title = schema.get("title").and_then(Value::as_str);
    let body = schema.get("description").and_then(Value::as_str);
    match (title, body) {
        (None, None) => None,
        (Some(t), None) => Some(t.to_owned()),
        (None, Some(b)) => Some(b.to_owned()),
        (Some(t), Some(b)) => Some(format!("{t}\n\n{b}")),
    }
}

/// A property's whole doc comment (its own, else its type's), intra-doc links reduced to
/// their text.
fn doc_text(schema: &Value, root: &Value) -> String {
    let text = description(schema)
        .or_else(|| description(resolved(schema, root)))
        .unwrap_or_default();
    strip_doc_links(&text)
}

/// `` [`Name`](path::to) `` and `` [`Name`] `` as `` `Name` `` (rustdoc's links mean nothing
/// on a Markdown page); web links are kept.
fn strip_doc_links(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('[') {
        out.push_str(&rest[..open]);
        let after = &rest[open + 1..];
        let Some(close) = after.find(']') else {
            out.push_str(&rest[open..]);
            return out;
        };
        let label = &after[..close];
        let tail = &after[close + 1..];
        if let Some(target) = tail.strip_prefix('(') {
            if let Some(end) = target.find(')') {
                let url = &target[..end];
                if url.starts_with("http") {
                    out.push_str(&format!("[{label}]({url})"));
                } else {
                    out.push_str(label);
                }
                rest = &target[end + 1..];
                continue;
            }
        }
        if label.starts_with('`') && label.ends_with('`') && label.len() > 1 {
            out.push_str(label);
        } else {
            out.push('[');
            out.push_str(label);
            out.push(']');
        }
        rest = tail;
    }
    out.push_str(rest);
    out
}

/// Text as one Markdown table cell: lines joined, paragraphs kept apart by a space, `|`
/// escaped.
fn cell(text: &str) -> String {
    text.split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn doc_links_become_their_text() {
        assert_eq!(
            strip_doc_links("see [`Foo`](crate::Foo) and [`Bar`], [a site](https://x.org) [1, 2]"),
            "see `Foo` and `Bar`, [a site](https://x.org) [1, 2]"
        );
    }

    #[test]
    fn cells_are_one_line_with_bars_escaped() {
        assert_eq!(cell("a |b|\n\n c"), "a \\|b\\| c");
    }
}
