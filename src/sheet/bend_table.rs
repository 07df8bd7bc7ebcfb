//! A bend table: the K-factor, bend allowance or bend deduction a shop measured for its
//! material by thickness, inner radius and bend angle, read from a CSV file and interpolated
//! multilinearly (piecewise-linear in each of the three variables) over the table's grid.
//!
//! The file has a header row naming its columns: `thickness`, `inner_radius`, `angle` (the bend
//! angle in degrees: how far the flange turns, 90 for an L) and exactly one of `k`, `ba`, `bd`,
//! with an optional `material`. Lengths are millimetres. For each material the rows must form a
//! full grid (every thickness with every radius and every angle): the value at a bend is the
//! multilinear interpolation of the (up to) eight rows around it, and a bend outside the grid
//! is refused, never extrapolated.

use std::path::Path;

use serde::{Deserialize, Serialize};

/// How far, in mm, a bend's thickness or radius may lie outside a table's grid and still be on
/// it (round-off of the CAD's geometry).
pub const TABLE_LENGTH_TOLERANCE_MM: f64 = 1e-4;

/// How far, in degrees, a bend's angle may lie outside a table's grid and still be on it.
pub const TABLE_ANGLE_TOLERANCE_DEGREES: f64 = 1e-3;

/// What a bend table gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TableQuantity {
    /// The K-factor: `BA = θ · (R + K · t)`.
    K,
    /// The bend allowance itself, mm.
    Ba,
    /// The bend deduction, mm: `BA = 2 · (R + t) · tan(θ/2) − BD`.
    Bd,
}

impl TableQuantity {
    /// The column's name in the header.
    pub fn column(self) -> &'static str {
        match self {
            Self::K => "k",
            Self::Ba => "ba",
            Self::Bd => "bd",
        }
    }
}

/// One row of a bend table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BendTableRow {
    /// The row's line in the file (the header is line 1).
    pub line: u64,
    /// The material the row is for (none when the table has no `material` column).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Sheet thickness, mm.
    pub thickness: f64,
    /// Inner bend radius, mm.
    pub inner_radius: f64,
    /// Bend angle, degrees.
    pub angle: f64,
    /// The K-factor, allowance or deduction (per the table's quantity).
    pub value: f64,
}

/// A bend table read from a CSV file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BendTable {
    /// The file it was read from, as given.
    pub file: String,
    /// What its value column gives.
    pub quantity: TableQuantity,
    /// Its rows, in file order.
    pub rows: Vec<BendTableRow>,
}

/// The table's value at one bend: the interpolated value and the lines of the rows it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct TableValue {
    /// The interpolated K-factor, allowance or deduction.
    pub value: f64,
    /// The lines of the rows with a non-zero weight, ascending.
    pub lines: Vec<u64>,
}

/// The columns a bend table may have.
const COLUMNS: [&str; 7] = [
    "material",
    "thickness",
    "inner_radius",
    "angle",
    "k",
    "ba",
    "bd",
];

impl BendTable {
    /// Reads and checks a bend table file; the error names the file and the line.
    pub fn read(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|error| format!("bend table {}: {error}", path.display()))?;
        Self::parse(&path.display().to_string(), &text)
    }

    /// Parses and checks a bend table's text; `file` names it in errors (`FILE line N: ...`).
    pub fn parse(file: &str, text: &str) -> Result<Self, String> {
        let at = |line: u64, reason: String| format!("bend table {file} line {line}: {reason}");
        let mut reader = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(text.as_bytes());
        let headers = reader
            .headers()
            .map_err(|error| at(1, error.to_string()))?
            .clone();
        let columns = header_columns(&headers).map_err(|reason| at(1, reason))?;
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|error| {
                let line = error.position().map_or(0, |position| position.line());
                at(line, error.to_string())
            })?;
            let line = record.position().map_or(0, |position| position.line());
            let row = row_of_record(&columns, &record, line).map_err(|reason| at(line, reason))?;
            rows.push(row);
        }
        let table = Self {
            file: file.to_owned(),
            quantity: columns.quantity,
            rows,
        };
        table.check_grid()?;
        Ok(table)
    }

    /// Whether the table has a `material` column.
    fn has_materials(&self) -> bool {
        self.rows.iter().any(|row| row.material.is_some())
    }

    /// The rows for `material` (all of them when the table has no `material` column).
    fn rows_for(&self, material: Option<&str>) -> Result<Vec<&BendTableRow>, String> {
        if !self.has_materials() {
            return Ok(self.rows.iter().collect());
        }
        let names = || {
            let mut names: Vec<&str> = self
                .rows
                .iter()
                .filter_map(|row| row.material.as_deref())
                .collect();
            names.dedup();
            names.join(", ")
        };
        let Some(material) = material else {
            return Err(format!(
                "bend table {} is by material ({}) and the part has none: give --material",
                self.file,
                names()
            ));
        };
        let rows: Vec<&BendTableRow> = self
            .rows
            .iter()
            .filter(|row| {
                row.material
                    .as_deref()
                    .is_some_and(|name| name.eq_ignore_ascii_case(material.trim()))
            })
            .collect();
        if rows.is_empty() {
            return Err(format!(
                "bend table {} has no rows for material {material:?} (it has {})",
                self.file,
                names()
            ));
        }
        Ok(rows)
    }

    /// Checks that each material's rows form a full grid with no row given twice.
    fn check_grid(&self) -> Result<(), String> {
        if self.rows.is_empty() {
            return Err(format!("bend table {}: no rows", self.file));
        }
        let mut materials: Vec<Option<String>> = self
            .rows
            .iter()
            .map(|row| row.material.as_ref().map(|m| m.to_lowercase()))
            .collect();
        materials.sort();
        materials.dedup();
        for material in &materials {
            let rows: Vec<&BendTableRow> = self
                .rows
                .iter()
                .filter(|row| &row.material.as_ref().map(|m| m.to_lowercase()) == material)
                .collect();
            check_material_grid(&self.file, &rows)?;
        }
        Ok(())
    }

    /// The table's value at a bend of `thickness` and `inner_radius` (mm), bent by
    /// `angle_degrees`, for `material`: multilinear over the grid cell around it. A bend outside
    /// the grid (beyond the tolerances) is an error naming the range.
    pub fn value_at(
        &self,
        material: Option<&str>,
        thickness: f64,
        inner_radius: f64,
        angle_degrees: f64,
    ) -> Result<TableValue, String> {
        let rows = self.rows_for(material)?;
        let grid = Grid::of(&rows);
        let on_axis = |name: &str, axis: &[f64], x: f64, tolerance: f64, unit: &str| {
            bracket(axis, x, tolerance).ok_or_else(|| {
                format!(
                    "bend table {}: a bend of {name} {x:.4}{unit} is outside the table's {} to {}{unit} (not extrapolated)",
                    self.file,
                    axis[0],
                    axis[axis.len() - 1]
                )
            })
        };
        let t = on_axis(
            "thickness",
            &grid.thicknesses,
            thickness,
            TABLE_LENGTH_TOLERANCE_MM,
            " mm",
        )?;
        let r = on_axis(
            "inner radius",
            &grid.radii,
            inner_radius,
            TABLE_LENGTH_TOLERANCE_MM,
            " mm",
        )?;
        let a = on_axis(
            "angle",
            &grid.angles,
            angle_degrees,
            TABLE_ANGLE_TOLERANCE_DEGREES,
            "°",
        )?;
        let mut value = 0.0;
        let mut lines = Vec::new();
        for (ti, tw) in t.corners() {
            for (ri, rw) in r.corners() {
                for (ai, aw) in a.corners() {
                    let weight = tw * rw * aw;
                    let row = grid.row(&rows, ti, ri, ai);
                    value += weight * row.value;
                    if weight > 0.0 {
                        lines.push(row.line);
                    }
                }
            }
        }
        lines.sort_unstable();
        lines.dedup();
        Ok(TableValue { value, lines })
    }
}

/// Where the header's columns are, and which value column it has.
struct Columns {
    material: Option<usize>,
    thickness: usize,
    inner_radius: usize,
    angle: usize,
    value: usize,
    quantity: TableQuantity,
}

/// The columns of a header, or why it is not a bend table's.
fn header_columns(headers: &csv::StringRecord) -> Result<Columns, String> {
    let position = |name: &str| headers.iter().position(|header| header == name);
    for (index, header) in headers.iter().enumerate() {
        if !COLUMNS.contains(&header) {
            return Err(format!(
                "unknown column {header:?} (the columns are {})",
                COLUMNS.join(", ")
            ));
        }
        if position(header) != Some(index) {
            return Err(format!("column {header:?} appears twice"));
        }
    }
    let required =
        |name: &str| position(name).ok_or_else(|| format!("the header has no `{name}` column"));
    let values: Vec<TableQuantity> = [TableQuantity::K, TableQuantity::Ba, TableQuantity::Bd]
        .into_iter()
        .filter(|quantity| position(quantity.column()).is_some())
        .collect();
    let [quantity] = values.as_slice() else {
        return Err("give exactly one value column: `k`, `ba` or `bd`".to_owned());
    };
    Ok(Columns {
        material: position("material"),
        thickness: required("thickness")?,
        inner_radius: required("inner_radius")?,
        angle: required("angle")?,
        value: required(quantity.column())?,
        quantity: *quantity,
    })
}

/// One row from its record, its numbers checked.
fn row_of_record(
    columns: &Columns,
    record: &csv::StringRecord,
    line: u64,
) -> Result<BendTableRow, String> {
    let number = |index: usize, name: &str| -> Result<f64, String> {
        let text = record.get(index).unwrap_or("");
        text.parse::<f64>()
            .ok()
            .filter(|value| value.is_finite())
            .ok_or_else(|| format!("`{name}` is {text:?}: give a number"))
    };
    let material = columns
        .material
        .map(|index| record.get(index).unwrap_or("").to_owned());
    if material.as_deref() == Some("") {
        return Err("`material` is empty".to_owned());
    }
    let row = BendTableRow {
        line,
        material,
        thickness: number(columns.thickness, "thickness")?,
        inner_radius: number(columns.inner_radius, "inner_radius")?,
        angle: number(columns.angle, "angle")?,
        value: number(columns.value, columns.quantity.column())?,
    };
    check_row(&row, columns.quantity)?;
    Ok(row)
}

/// Checks a row's ranges.
fn check_row(row: &BendTableRow, quantity: TableQuantity) -> Result<(), String> {
    if row.thickness <= 0.0 {
        return Err(format!("thickness {} must be above 0", row.thickness));
    }
    if row.inner_radius < 0.0 {
        return Err(format!(
            "inner_radius {} must not be negative",
            row.inner_radius
        ));
    }
    if !(row.angle > 0.0 && row.angle <= 180.0) {
        return Err(format!(
            "angle {} must be above 0 and at most 180",
            row.angle
        ));
    }
    match quantity {
        TableQuantity::K if !(0.0..=1.0).contains(&row.value) => {
            Err(format!("k {} must be 0 to 1", row.value))
        }
        TableQuantity::Ba if row.value < 0.0 => {
            Err(format!("ba {} must not be negative", row.value))
        }
        TableQuantity::Bd if row.angle >= 180.0 => Err(
            "a bend deduction is measured to the virtual sharp, which a 180° bend does not have: give k or ba"
                .to_owned(),
        ),
        _ => Ok(()),
    }
}

/// The sorted distinct values of one variable over some rows.
fn axis(rows: &[&BendTableRow], value: impl Fn(&BendTableRow) -> f64) -> Vec<f64> {
    let mut values: Vec<f64> = rows.iter().map(|row| value(row)).collect();
    values.sort_by(f64::total_cmp);
    values.dedup();
    values
}

/// A material's grid: its thicknesses, radii and angles, and the row at each node.
struct Grid {
    thicknesses: Vec<f64>,
    radii: Vec<f64>,
    angles: Vec<f64>,
    nodes: Vec<Option<usize>>,
}

impl Grid {
    /// The grid of some rows (the last row at a node when given twice).
    fn of(rows: &[&BendTableRow]) -> Self {
        let thicknesses = axis(rows, |row| row.thickness);
        let radii = axis(rows, |row| row.inner_radius);
        let angles = axis(rows, |row| row.angle);
        let mut grid = Self {
            nodes: vec![None; thicknesses.len() * radii.len() * angles.len()],
            thicknesses,
            radii,
            angles,
        };
        for (index, row) in rows.iter().enumerate() {
            let node = grid.node_of(row);
            grid.nodes[node] = Some(index);
        }
        grid
    }

    /// The node index of grid indices.
    fn node(&self, t: usize, r: usize, a: usize) -> usize {
        (t * self.radii.len() + r) * self.angles.len() + a
    }

    /// The node a row is at.
    fn node_of(&self, row: &BendTableRow) -> usize {
        let index = |axis: &[f64], x: f64| axis.iter().position(|&v| v == x).unwrap_or(0);
        self.node(
            index(&self.thicknesses, row.thickness),
            index(&self.radii, row.inner_radius),
            index(&self.angles, row.angle),
        )
    }

    /// The row at a node of a full grid.
    fn row<'a>(&self, rows: &[&'a BendTableRow], t: usize, r: usize, a: usize) -> &'a BendTableRow {
        let node = self.nodes[self.node(t, r, a)].unwrap_or(0);
        rows[node]
    }
}

/// Checks one material's rows: no node given twice, every node given.
fn check_material_grid(file: &str, rows: &[&BendTableRow]) -> Result<(), String> {
    let grid = Grid::of(rows);
    let mut seen: Vec<Option<u64>> = vec![None; grid.nodes.len()];
    for row in rows {
        let node = grid.node_of(row);
        if let Some(first) = seen[node] {
            return Err(format!(
                "bend table {file} line {}: the same thickness, inner radius and angle as line {first}",
                row.line
            ));
        }
        seen[node] = Some(row.line);
    }
    for (t, &thickness) in grid.thicknesses.iter().enumerate() {
        for (r, &radius) in grid.radii.iter().enumerate() {
            for (a, &angle) in grid.angles.iter().enumerate() {
                if seen[grid.node(t, r, a)].is_none() {
                    let material = rows[0]
                        .material
                        .as_ref()
                        .map_or(String::new(), |m| format!(" for material {m:?}"));
                    return Err(format!(
                        "bend table {file}: no row{material} for thickness {thickness}, inner_radius {radius}, angle {angle}: the rows must form a full grid (every thickness with every radius and angle) to be interpolated"
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Where `x` lies on an axis: the two nodes around it and the weight of the upper one; `None`
/// outside the axis' range by more than `tolerance`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Bracket {
    low: usize,
    high: usize,
    weight: f64,
}

impl Bracket {
    /// The bracket's nodes with their weights (one node when it sits on a node).
    fn corners(&self) -> impl Iterator<Item = (usize, f64)> {
        let both = [(self.low, 1.0 - self.weight), (self.high, self.weight)];
        let count = if self.low == self.high { 1 } else { 2 };
        both.into_iter().take(count)
    }
}

/// The bracket of `x` on a sorted axis.
fn bracket(axis: &[f64], x: f64, tolerance: f64) -> Option<Bracket> {
    let (first, last) = (axis[0], axis[axis.len() - 1]);
    if !(x >= first - tolerance && x <= last + tolerance) {
        return None;
    }
    if let Some(node) = axis.iter().position(|&v| (v - x).abs() <= tolerance) {
        return Some(Bracket {
            low: node,
            high: node,
            weight: 0.0,
        });
    }
    let high = axis.iter().position(|&v| v > x)?;
    let low = high - 1;
    Some(Bracket {
        low,
        high,
        weight: (x - axis[low]) / (axis[high] - axis[low]),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLE: &str = "material,thickness,inner_radius,angle,k\n\
        steel,1,1,90,0.30\n\
        steel,1,1,120,0.34\n\
        steel,1,3,90,0.40\n\
        steel,1,3,120,0.44\n\
        steel,2,1,90,0.36\n\
        steel,2,1,120,0.40\n\
        steel,2,3,90,0.46\n\
        steel,2,3,120,0.50\n\
        alu,2,2,90,0.45\n";

    #[test]
    fn a_grid_point_gives_its_row() {
        let table = BendTable::parse("t.csv", TABLE).unwrap();
        let value = table.value_at(Some("Steel"), 2.0, 3.0, 90.0).unwrap();
        assert_eq!(value.value, 0.46);
        assert_eq!(value.lines, vec![8]);
    }

    #[test]
    fn a_midpoint_is_the_mean_of_its_eight_corners() {
        let table = BendTable::parse("t.csv", TABLE).unwrap();
        let value = table.value_at(Some("steel"), 1.5, 2.0, 105.0).unwrap();
        let mean = (0.30 + 0.34 + 0.40 + 0.44 + 0.36 + 0.40 + 0.46 + 0.50) / 8.0;
        assert!((value.value - mean).abs() < 1e-12);
        assert_eq!(value.lines, (2..=9).collect::<Vec<_>>());
        let quarter = table.value_at(Some("steel"), 1.0, 1.5, 90.0).unwrap();
        assert!((quarter.value - (0.75 * 0.30 + 0.25 * 0.40)).abs() < 1e-12);
    }

    #[test]
    fn a_single_value_axis_must_be_met() {
        let table = BendTable::parse("t.csv", TABLE).unwrap();
        assert_eq!(
            table.value_at(Some("ALU"), 2.0, 2.0, 90.0).unwrap().value,
            0.45
        );
        let error = table.value_at(Some("alu"), 2.0, 2.0, 91.0).unwrap_err();
        assert!(
            error.contains("angle 91.0000° is outside the table's 90 to 90°"),
            "{error}"
        );
    }

    #[test]
    fn a_bend_outside_the_grid_is_refused() {
        let table = BendTable::parse("t.csv", TABLE).unwrap();
        let error = table.value_at(Some("steel"), 2.5, 2.0, 90.0).unwrap_err();
        assert!(
            error.contains("thickness 2.5000 mm is outside the table's 1 to 2 mm"),
            "{error}"
        );
        let error = table.value_at(Some("copper"), 2.0, 2.0, 90.0).unwrap_err();
        assert!(error.contains("no rows for material \"copper\""), "{error}");
        let error = table.value_at(None, 2.0, 2.0, 90.0).unwrap_err();
        assert!(error.contains("give --material"), "{error}");
    }

    #[test]
    fn malformed_tables_are_refused_with_the_line() {
        let cases = [
            (
                "thickness,inner_radius,angle\n1,1,90\n",
                "line 1: give exactly one value column",
            ),
            (
                "thickness,inner_radius,angle,k,ba\n1,1,90,0.4,2\n",
                "line 1: give exactly one",
            ),
            (
                "thickness,radius,angle,k\n1,1,90,0.4\n",
                "line 1: unknown column \"radius\"",
            ),
            (
                "thickness,inner_radius,angle,k\n1,1,90,0.4\n1,x,90,0.4\n",
                "line 3: `inner_radius` is \"x\"",
            ),
            (
                "thickness,inner_radius,angle,k\n1,1,90,1.4\n",
                "line 2: k 1.4 must be 0 to 1",
            ),
            (
                "thickness,inner_radius,angle,k\n1,1,90,0.4\n1,1,90,0.5\n",
                "line 3: the same thickness",
            ),
            (
                "thickness,inner_radius,angle,k\n1,1,90,0.4\n2,2,90,0.5\n",
                "no row for thickness 1, inner_radius 2",
            ),
            (
                "thickness,inner_radius,angle,bd\n1,1,180,2\n",
                "line 2: a bend deduction",
            ),
            ("thickness,inner_radius,angle,k\n1,1,90\n", "line 2:"),
            ("thickness,inner_radius,angle,k\n", "no rows"),
        ];
        for (text, expected) in cases {
            let error = BendTable::parse("t.csv", text).unwrap_err();
            assert!(error.contains(expected), "{text:?}: {error}");
            assert!(error.starts_with("bend table t.csv"), "{error}");
        }
    }
}
