//! OBJ loading: small files written into a temporary directory.

use morgana::geometry::DVec3;
use morgana::geometry::mesh::load_obj;
use std::path::PathBuf;

/// An OBJ file in a per-test temporary directory, removed on drop.
struct TempObj {
    dir: PathBuf,
    path: PathBuf,
}

impl Drop for TempObj {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Writes `text` to a fresh file in a per-test temporary directory.
fn obj_file(test: &str, text: &str) -> TempObj {
    let dir = std::env::temp_dir().join(format!("morgana-geometry-mesh-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(format!("{test}.obj"));
    std::fs::write(&path, text).expect("write OBJ");
    TempObj { dir, path }
}

fn error_of(test: &str, text: &str) -> String {
    let file = obj_file(test, text);
    let err = load_obj(&file.path).expect_err("should fail");
    assert!(err.contains(&file.path.display().to_string()), "message does not name the file: {err}");
    err
}

#[test]
fn loads_all_faces_of_all_objects() {
    let text = "\
# a unit square as one quad face, and a triangle in a second object
mtllib missing.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vn 0 0 1
vt 0 0
o square
usemtl nothing
f 1/1/1 2/1/1 3/1/1 4/1/1
o roof
v 0 0 1
v 2 0 1
v 0 3 1
f -3 -2 -1
";
    let tris = load_obj(&obj_file("all_faces", text).path).expect("valid OBJ");
    assert_eq!(tris.len(), 3);
    let area: f64 = tris.iter().map(|t| 0.5 * (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]).length()).sum();
    assert!((area - (1.0 + 3.0)).abs() < 1e-12, "area {area}");
    // The fan of the quad keeps its winding: both normals +z.
    for t in &tris[..2] {
        let n = (t.p[1] - t.p[0]).cross(t.p[2] - t.p[0]);
        assert!(n.z > 0.0);
    }
    let roof = &tris[2];
    assert_eq!(roof.p, [DVec3::new(0.0, 0.0, 1.0), DVec3::new(2.0, 0.0, 1.0), DVec3::new(0.0, 3.0, 1.0)]);
}

#[test]
fn crlf_line_endings_are_read() {
    let tris = load_obj(&obj_file("crlf", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n").path).expect("valid");
    assert_eq!(tris.len(), 1);
}

#[test]
fn missing_file_is_an_error() {
    let path = std::env::temp_dir().join("morgana-geometry-mesh-does-not-exist.obj");
    let err = load_obj(&path).expect_err("missing file");
    assert!(err.contains("cannot open") && err.contains("does-not-exist"), "{err}");
}

#[test]
fn parse_errors_carry_tobjs_message_and_the_line() {
    let err = error_of("parse", "v 0 0 0\nv 1 0 0\nv 1 abc 0\nf 1 2 3\n");
    assert!(err.contains(":3:") && err.contains("position parse error"), "{err}");
    let err = error_of("bad_face", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n");
    assert!(err.contains(":4:") && err.contains("face parse error"), "{err}");
}

#[test]
fn face_index_out_of_bounds_is_an_error() {
    let err = error_of("bounds", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    assert!(err.contains("out of bounds"), "{err}");
}

#[test]
fn a_file_without_triangles_is_an_error() {
    let err = error_of("empty", "# nothing\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    assert!(err.contains("no triangles"), "{err}");
}

#[test]
fn non_finite_vertices_are_an_error() {
    let err = error_of("nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(err.contains("not finite"), "{err}");
    // 1e400 overflows even tobj's f64 (the `use_f64` feature) to infinity.
    let err = error_of("inf", "v 0 0 0\nv 1e400 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(err.contains("not finite"), "{err}");
}

#[test]
fn degenerate_triangles_are_dropped_and_only_degenerate_is_an_error() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n";
    let tris = load_obj(&obj_file("some_degenerate", text).path).expect("one good triangle");
    assert_eq!(tris.len(), 1);
    assert_eq!(tris[0].p, [DVec3::ZERO, DVec3::X, DVec3::Y]);
    let err = error_of("all_degenerate", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 1 1 2\n");
    assert!(err.contains("all 2 triangles are degenerate"), "{err}");
}
