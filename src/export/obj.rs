//! OBJ output of the facet model that was flattened (3D) and of its pattern (2D, z = 0), with the
//! same vertices and faces in the same order, so anyone can recompute `E_S` and `E_C`.
//! Coordinates are printed with 17 significant digits (exact f64 round trip), faces 1-based.

use std::fmt::Write;

use glam::{DVec2, DVec3};

/// OBJ text of a 3D mesh.
pub fn mesh_obj(header: &str, positions: &[DVec3], triangles: &[[u32; 3]]) -> String {
    let mut text = comment_lines(header);
    for p in positions {
        let _ = writeln!(text, "v {} {} {}", p.x, p.y, p.z);
    }
    push_faces(&mut text, triangles);
    text
}

/// OBJ text of a flat pattern (z = 0).
pub fn pattern_obj(header: &str, positions: &[DVec2], triangles: &[[u32; 3]]) -> String {
    let mut text = comment_lines(header);
    for p in positions {
        let _ = writeln!(text, "v {} {} 0", p.x, p.y);
    }
    push_faces(&mut text, triangles);
    text
}

fn comment_lines(header: &str) -> String {
    header.lines().map(|line| format!("# {line}\n")).collect()
}

fn push_faces(text: &mut String, triangles: &[[u32; 3]]) {
    for [a, b, c] in triangles {
        let _ = writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1);
    }
}

#[cfg(test)]
mod tests {
    use crate::export::obj::*;

    #[test]
    fn round_trips_through_the_obj_reader() {
        let positions = vec![
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.0 / 3.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 1e-17),
        ];
        let text = mesh_obj("test", &positions, &[[0, 1, 2]]);
        let soup = crate::ingest::parse_obj(text.as_bytes()).expect("parses");
        assert_eq!(soup.positions, positions);
        assert_eq!(soup.triangles, vec![[0, 1, 2]]);
    }
}
