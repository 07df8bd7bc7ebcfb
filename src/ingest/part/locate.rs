//! Locating a part file's defects: the line and field a parse error or a build defect is at.

use std::ops::Range;
use std::path::Path;

use super::errors::PartError;
use super::spec;

/// 1-based line of byte `offset`.
pub fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// The key assigned on the line holding byte `offset`, if the line is `key = value`.
fn key_on_line(text: &str, offset: usize) -> Option<String> {
    let start = text[..offset.min(text.len())]
        .rfind('\n')
        .map_or(0, |i| i + 1);
    let line = text[start..].lines().next()?;
    let (key, _) = line.split_once('=')?;
    let key = key.trim();
    (!key.is_empty() && !key.starts_with('[')).then(|| key.to_string())
}

pub fn syntax_error(path: &Path, text: &str, error: &toml::de::Error) -> PartError {
    let message = error.message().trim().to_string();
    let start = error.span().map_or(0, |s| s.start.min(text.len()));
    // Errors inside a surface table (buffered to read its `kind`) carry the table's span, not
    // the field's: the first name the message quotes locates the field within the table.
    let quoted = message.split('`').nth(1).unwrap_or_default();
    let (line, field) = if let Some(found) = (!quoted.is_empty())
        .then(|| find_key(&text[start..], quoted))
        .flatten()
    {
        (line_of(text, start + found), quoted.to_string())
    } else if let Some(found) = (!quoted.is_empty())
        .then(|| text[start..].find(&format!("\"{quoted}\"")))
        .flatten()
    {
        let offset = start + found;
        (
            line_of(text, offset),
            key_on_line(text, offset).unwrap_or_default(),
        )
    } else {
        let field = key_on_line(text, start).unwrap_or_else(|| {
            if message.starts_with("missing field") {
                quoted.to_string()
            } else {
                String::new()
            }
        });
        (line_of(text, start), field)
    };
    let (line, field) = if field.is_empty() {
        surface_field(text, start).unwrap_or((line, field))
    } else {
        (line, field)
    };
    PartError {
        path: path.to_path_buf(),
        line: error.span().map(|_| line),
        field,
        message,
    }
}

/// The line and field of a type or length error inside the `[[surface]]` table whose header
/// starts at `start`. Such errors come from a buffered read (the `kind` picks the type) and carry
/// the whole table's span; reading the table again as its kind's own type locates the value.
fn surface_field(text: &str, start: usize) -> Option<(usize, String)> {
    let header = text[start..].trim_start();
    if !header.starts_with("[[surface]]") {
        return None;
    }
    let body_start = start + text[start..].find('\n')? + 1;
    let body = &text[body_start..table_end(text, body_start)];
    let kind_at = find_key(body, "kind")?;
    let kind_end = body[kind_at..]
        .find('\n')
        .map_or(body.len(), |n| kind_at + n);
    // The body without its `kind` line, blanked so that offsets stay the same.
    let mut without_kind = body.to_string();
    without_kind.replace_range(kind_at..kind_end, &" ".repeat(kind_end - kind_at));
    let kind: String = toml::from_str::<toml::Table>(body)
        .ok()?
        .get("kind")?
        .as_str()?
        .to_string();
    let error = match kind.as_str() {
        "polygon" => toml::from_str::<spec::PolygonSpec>(&without_kind).err(),
        "cylinder" => toml::from_str::<spec::CylinderSpec>(&without_kind).err(),
        "cone" => toml::from_str::<spec::ConeSpec>(&without_kind).err(),
        "revolution" => toml::from_str::<spec::RevolutionSpec>(&without_kind).err(),
        "bspline" => toml::from_str::<spec::BsplineSpec>(&without_kind).err(),
        "loft" => toml::from_str::<spec::LoftSpec>(&without_kind).err(),
        "extrusion" => toml::from_str::<spec::ExtrusionSpec>(&without_kind).err(),
        _ => None,
    }?;
    let offset = body_start + error.span()?.start;
    let index = text[..start].matches("[[surface]]").count();
    let key = key_at_or_before(text, offset, body_start)?;
    Some((line_of(text, offset), format!("surface[{index}].{key}")))
}

/// The key of the `key = value` line holding byte `offset`, or of the nearest such line above it
/// (a value written over several lines), not above `floor`.
fn key_at_or_before(text: &str, offset: usize, floor: usize) -> Option<String> {
    let mut line_start = text[..offset.min(text.len())]
        .rfind('\n')
        .map_or(0, |i| i + 1);
    loop {
        if let Some(key) = key_on_line(text, line_start)
            && key.chars().all(|c| c.is_alphanumeric() || c == '_')
        {
            return Some(key);
        }
        if line_start <= floor {
            return None;
        }
        line_start = text[..line_start - 1].rfind('\n').map_or(0, |i| i + 1);
    }
}

/// The line of `field` (its last named component, then its first) inside the table at `span`;
/// the table's first line when neither is written there.
pub fn field_line(text: &str, span: Range<usize>, field: &str) -> usize {
    let names: Vec<&str> = field
        .split('.')
        .map(|part| part.split('[').next().unwrap_or(part))
        .filter(|name| !name.is_empty())
        .collect();
    let start = span.start.min(text.len());
    let table = &text[start..table_end(text, start).max(span.end.min(text.len()))];
    for name in names.iter().rev().chain(names.first()) {
        if let Some(position) = find_key(table, name) {
            return line_of(text, start + position);
        }
    }
    line_of(text, start)
}

/// The end of the table whose header or body starts at `start`: the next line that opens a
/// table (`[name]` or `[[name]]`, not the continuation of a multi-line array), or the end of the
/// text.
pub fn table_end(text: &str, start: usize) -> usize {
    let opens_table = |line: &str| {
        let line = line.trim_start();
        let name = line.trim_start_matches('[').trim_start();
        line.starts_with('[')
            && line.len() - name.len() <= 2
            && name.starts_with(|c: char| c.is_alphabetic() || c == '_' || c == '"')
    };
    let mut offset = start;
    for (index, line) in text[start..].split_inclusive('\n').enumerate() {
        if index > 0 && opens_table(line) {
            return offset;
        }
        offset += line.len();
    }
    text.len()
}

/// Byte position of `name` used as a key (`name =`) in `table`.
pub fn find_key(table: &str, name: &str) -> Option<usize> {
    let mut search_from = 0;
    while let Some(found) = table[search_from..].find(name) {
        let position = search_from + found;
        let before = table[..position].chars().next_back();
        let after = table[position + name.len()..].trim_start();
        let starts_word = before.is_none_or(|c| !(c.is_alphanumeric() || c == '_'));
        if starts_word && after.starts_with('=') {
            return Some(position);
        }
        search_from = position + name.len();
    }
    None
}
