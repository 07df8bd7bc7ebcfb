//! The entity instances of a STEP file's data section, read with a light scanner of our own
//! (names, references and the raw text of each instance), for what truck-stepio does not do:
//! naming unreadable entities, finding the units and placements of the geometry.

use std::collections::BTreeMap;

/// One entity instance `#id = NAME(...)` of the data section.
#[derive(Debug, Clone, PartialEq)]
pub struct Statement {
    /// Its entity names (several for a complex instance `(A(...) B(...))`).
    pub names: Vec<String>,
    /// The instances it refers to, in order.
    pub references: Vec<u64>,
    /// The text after `=`, trimmed.
    pub body: String,
}

impl Statement {
    /// Whether one of its names is `name`.
    pub fn is(&self, name: &str) -> bool {
        self.names.iter().any(|n| n == name)
    }
}

/// Every entity instance of the data section, by id, with the instances that refer to each.
#[derive(Debug, Clone, Default)]
pub struct Statements {
    by_id: BTreeMap<u64, Statement>,
    referrers: BTreeMap<u64, Vec<u64>>,
}

impl Statements {
    /// Scans the exchange text of a STEP file (comments dropped by
    /// `text.rs`; see [`Statement`]).
    pub fn parse(text: &str) -> Self {
        let mut by_id = BTreeMap::new();
        for statement in split_statements(text) {
            let Some(rest) = statement.strip_prefix('#') else {
                continue;
            };
            let Some((id, body)) = rest.split_once('=') else {
                continue;
            };
            let Ok(id) = id.trim().parse::<u64>() else {
                continue;
            };
            let body = body.trim();
            by_id.insert(
                id,
                Statement {
                    names: entity_names(body),
                    references: references(body),
                    body: body.to_string(),
                },
            );
        }
        let mut referrers: BTreeMap<u64, Vec<u64>> = BTreeMap::new();
        for (id, statement) in &by_id {
            for reference in &statement.references {
                referrers.entry(*reference).or_default().push(*id);
            }
        }
        Self { by_id, referrers }
    }

    /// The instance `#id`.
    pub fn get(&self, id: &u64) -> Option<&Statement> {
        self.by_id.get(id)
    }

    /// Every instance, in id order.
    pub fn iter(&self) -> impl Iterator<Item = (&u64, &Statement)> {
        self.by_id.iter()
    }

    /// The instances that refer to `#id`, in id order.
    pub fn referrers(&self, id: u64) -> &[u64] {
        self.referrers.get(&id).map_or(&[], Vec::as_slice)
    }
}

/// The statements of the file (`;`-terminated, outside quoted strings); the text comes without
/// comments (`text.rs`).
fn split_statements(text: &str) -> Vec<String> {
    let mut statements = Vec::new();
    let mut current = String::new();
    let mut quoted = false;
    for c in text.chars() {
        match c {
            '\'' => {
                quoted = !quoted;
                current.push(c);
            }
            ';' if !quoted => statements.push(std::mem::take(&mut current).trim().to_string()),
            _ => current.push(c),
        }
    }
    statements
}

/// The entity names of an instance's body: `NAME(...)`, or each name of a complex instance
/// `(A(...) B(...))`.
fn entity_names(body: &str) -> Vec<String> {
    let mut names = Vec::new();
    if let Some(complex) = body.strip_prefix('(') {
        let mut depth = 0usize;
        let mut word = String::new();
        let mut quoted = false;
        for c in complex.chars() {
            match c {
                '\'' => quoted = !quoted,
                _ if quoted => {}
                '(' => {
                    if depth == 0 && !word.trim().is_empty() {
                        names.push(word.trim().to_string());
                    }
                    word.clear();
                    depth += 1;
                }
                ')' => depth = depth.saturating_sub(1),
                _ if depth == 0 => word.push(c),
                _ => {}
            }
        }
    } else if let Some((name, _)) = body.split_once('(') {
        names.push(name.trim().to_string());
    }
    names
}

/// The `#id` references of a statement's body, in order (outside quoted strings).
fn references(body: &str) -> Vec<u64> {
    let mut found = Vec::new();
    let mut quoted = false;
    let mut chars = body.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\'' => quoted = !quoted,
            '#' if !quoted => {
                let mut digits = String::new();
                while let Some(d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                    digits.push(*d);
                    chars.next();
                }
                if let Ok(id) = digits.parse() {
                    found.push(id);
                }
            }
            _ => {}
        }
    }
    found
}

/// The numbers written as `KEYWORD(number)` in a body, e.g. the value of
/// `LENGTH_MEASURE(25.4)`.
pub fn measure_value(body: &str, keyword: &str) -> Option<f64> {
    let compact: String = body.chars().filter(|c| !c.is_whitespace()).collect();
    let start = compact.find(&format!("{keyword}("))? + keyword.len() + 1;
    let end = compact[start..].find(')')? + start;
    compact[start..end].parse().ok()
}

#[cfg(test)]
mod tests {
    use crate::ingest::step::statements::*;
    use crate::ingest::step::text::exchange_text;

    #[test]
    fn instances_complex_instances_comments_and_strings_are_scanned() {
        let text = "DATA;\n/* a comment; with #9 */\n#1=PRODUCT('a;b #7','',(#2));\n\
                    #2=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n\
                    #3 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE( 2.54E1 ),#2);\nENDSEC;";
        let statements = Statements::parse(&exchange_text(text.as_bytes()));
        let product = statements.get(&1).expect("#1");
        assert_eq!(product.names, vec!["PRODUCT"]);
        assert_eq!(product.references, vec![2]);
        assert_eq!(
            statements.get(&2).expect("#2").names,
            vec!["LENGTH_UNIT", "NAMED_UNIT", "SI_UNIT"]
        );
        assert_eq!(statements.referrers(2), &[1, 3]);
        assert_eq!(
            measure_value(&statements.get(&3).expect("#3").body, "LENGTH_MEASURE"),
            Some(25.4)
        );
        assert!(statements.get(&9).is_none());
    }
}
