//! Triangle meshes from Wavefront OBJ files (via tobj).
//!
//! Every face of every object is read, polygons fan-triangulated by tobj. Vertex positions
//! are converted to f64 (tobj reads them as f32 unless its `use_f64` feature is on: about seven
//! significant digits, 0.06 m at 1e6 m from the origin). Materials, normals and texture
//! coordinates are ignored. Triangles of zero area are dropped; a non-finite vertex, a file
//! without triangles, or one whose triangles are all degenerate is an error.

use super::{DVec3, Triangle};
use std::fs::File;
use std::io::{self, BufRead, BufReader, Read};
use std::path::Path;

/// All triangles of all models in an OBJ file; an error message says what is wrong.
pub fn load_obj(path: &Path) -> Result<Vec<Triangle>, String> {
    let name = path.display();
    let file = File::open(path).map_err(|e| format!("{name}: cannot open OBJ file: {e}"))?;
    let mut reader = LineCounter::new(BufReader::new(file));
    let options = tobj::LoadOptions { triangulate: true, single_index: true, ..Default::default() };
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| Ok(Default::default()))
        .map_err(|e| parse_error(&name.to_string(), &e, reader.line))?;
    let mut triangles = Vec::new();
    let mut degenerate = 0usize;
    for model in &models {
        for triangle in model_triangles(model).map_err(|e| format!("{name}: {e}"))? {
            if triangle.check().is_ok() {
                triangles.push(triangle);
            } else {
                degenerate += 1;
            }
        }
    }
    match (triangles.is_empty(), degenerate) {
        (true, 0) => Err(format!("{name}: no triangles (the file has no faces)")),
        (true, n) => Err(format!("{name}: all {n} triangles are degenerate (zero area)")),
        _ => Ok(triangles),
    }
}

/// tobj's message, with the line when the error belongs to one line. Index errors are found
/// when an object ends, so they carry no line.
fn parse_error(name: &str, e: &tobj::LoadError, line: usize) -> String {
    use tobj::LoadError::*;
    match e {
        FaceVertexOutOfBounds
        | FaceTexCoordOutOfBounds
        | FaceNormalOutOfBounds
        | FaceColorOutOfBounds
        | InvalidPolygon => {
            format!("{name}: OBJ error: {e} (a face refers to an element the file does not define)")
        }
        _ => format!("{name}:{line}: OBJ parse error: {e}"),
    }
}

/// The triangles of one tobj model (single-index, triangulated).
fn model_triangles(model: &tobj::Model) -> Result<Vec<Triangle>, String> {
    let mesh = &model.mesh;
    let vertex = |i: u32| -> Result<DVec3, String> {
        let k = 3 * i as usize;
        let xyz = mesh
            .positions
            .get(k..k + 3)
            .ok_or_else(|| format!("object \"{}\": face vertex {i} is missing", model.name))?;
        let p = DVec3::new(xyz[0], xyz[1], xyz[2]);
        if p.is_finite() { Ok(p) } else { Err(format!("object \"{}\": vertex {p} is not finite", model.name)) }
    };
    mesh.indices.chunks_exact(3).map(|f| Ok(Triangle { p: [vertex(f[0])?, vertex(f[1])?, vertex(f[2])?] })).collect()
}

/// A buffered reader that knows which line it is reading (1-based), for error messages.
struct LineCounter {
    inner: BufReader<File>,
    line: usize,
    at_line_start: bool,
}

impl LineCounter {
    fn new(inner: BufReader<File>) -> LineCounter {
        LineCounter { inner, line: 0, at_line_start: true }
    }
}

/// Advances the line count over `bytes`.
fn count_lines(line: &mut usize, at_line_start: &mut bool, bytes: &[u8]) {
    for &b in bytes {
        if *at_line_start {
            *line += 1;
        }
        *at_line_start = b == b'\n';
    }
}

impl Read for LineCounter {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        count_lines(&mut self.line, &mut self.at_line_start, &buf[..n]);
        Ok(n)
    }
}

impl BufRead for LineCounter {
    fn fill_buf(&mut self) -> io::Result<&[u8]> {
        self.inner.fill_buf()
    }

    fn consume(&mut self, amt: usize) {
        let buffer = self.inner.buffer();
        let consumed = &buffer[..amt.min(buffer.len())];
        count_lines(&mut self.line, &mut self.at_line_start, consumed);
        self.inner.consume(amt);
    }
}
