//! STL import, binary and ASCII, into a closed [`TriangleMesh`] (coordinates taken as mm).
//!
//! Exception to "use a library": the `stl_io` crate reads both formats but reports faults
//! without the line and column we owe the user, and adding a dependency for two small
//! formats is not indispensable. The formats:
//! - binary: an 80-byte header, a little-endian u32 triangle count n, then n records of
//!   50 bytes (normal, three vertices as 12 f32, a u16 attribute); the file size must be
//!   exactly 84 + 50 n;
//! - ASCII: `solid [name]`, then per facet `facet normal nx ny nz`, `outer loop`, three
//!   `vertex x y z`, `endloop`, `endfacet`, and finally `endsolid [name]`.
//!
//! A file whose size matches the binary layout is read as binary even if its header begins
//! with "solid" (many exporters do that); otherwise a file beginning with "solid" is ASCII.
//! Normals are ignored: the inside test does not need them.

use std::path::Path;

use super::error::ShapeError;
use super::triangle_mesh::TriangleMesh;

const BINARY_HEADER_BYTES: usize = 80;
const BINARY_PREAMBLE_BYTES: usize = BINARY_HEADER_BYTES + 4;
const BINARY_RECORD_BYTES: usize = 50;

/// Reads the STL file at `path` (binary or ASCII) and checks that the mesh is closed.
pub fn read_stl(path: &Path) -> Result<TriangleMesh, ShapeError> {
    let bytes = std::fs::read(path).map_err(|e| ShapeError::Unreadable {
        path: path.to_path_buf(),
        reason: e.to_string(),
    })?;
    parse_stl(path, &bytes)
}

/// Parses STL `bytes` as if read from `path` (the path is used in messages only).
pub fn parse_stl(path: &Path, bytes: &[u8]) -> Result<TriangleMesh, ShapeError> {
    let declared = (bytes.len() >= BINARY_PREAMBLE_BYTES).then(|| {
        let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        BINARY_PREAMBLE_BYTES + BINARY_RECORD_BYTES * count
    });
    let looks_ascii = bytes
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .is_some_and(|start| bytes[start..].starts_with(b"solid"));
    let triangles = if declared == Some(bytes.len()) || !looks_ascii {
        parse_binary(path, bytes)?
    } else {
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let as_binary = declared.map_or(String::new(), |n| {
                format!(
                    "; read as binary, its header declares {n} bytes but the file has {}",
                    bytes.len()
                )
            });
            ShapeError::MalformedAscii {
                path: path.to_path_buf(),
                line: 1 + bytes[..e.valid_up_to()]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count(),
                column: 1,
                reason: format!("starts with 'solid' but is not UTF-8 text{as_binary}"),
            }
        })?;
        parse_ascii(path, text)?
    };
    TriangleMesh::from_triangles(path, &triangles)
}

fn parse_binary(path: &Path, bytes: &[u8]) -> Result<Vec<[[f64; 3]; 3]>, ShapeError> {
    let fail = |offset: usize, reason: String| ShapeError::MalformedBinary {
        path: path.to_path_buf(),
        offset,
        reason,
    };
    if bytes.len() < BINARY_PREAMBLE_BYTES {
        return Err(fail(
            bytes.len(),
            format!(
                "the file has {} bytes, fewer than the {BINARY_PREAMBLE_BYTES}-byte binary \
                 header, and does not start with 'solid'",
                bytes.len()
            ),
        ));
    }
    let count = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
    let expected = BINARY_PREAMBLE_BYTES + BINARY_RECORD_BYTES * count;
    if expected != bytes.len() {
        return Err(fail(
            BINARY_HEADER_BYTES,
            format!(
                "the header declares {count} triangles ({expected} bytes) but the file has {} bytes",
                bytes.len()
            ),
        ));
    }
    let mut triangles = Vec::with_capacity(count);
    for t in 0..count {
        let record = BINARY_PREAMBLE_BYTES + t * BINARY_RECORD_BYTES;
        let mut tri = [[0.0; 3]; 3];
        for (v, vertex) in tri.iter_mut().enumerate() {
            for (a, coord) in vertex.iter_mut().enumerate() {
                // Skip the 12-byte normal, then 12 bytes per vertex.
                let at = record + 12 + 12 * v + 4 * a;
                let x =
                    f32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
                if !x.is_finite() {
                    return Err(fail(
                        at,
                        format!(
                            "triangle {} vertex {} has a non-finite coordinate {x}",
                            t + 1,
                            v + 1
                        ),
                    ));
                }
                *coord = f64::from(x);
            }
        }
        triangles.push(tri);
    }
    Ok(triangles)
}

/// A whitespace-separated word with its 1-based line and column.
struct Token<'a> {
    text: &'a str,
    line: usize,
    column: usize,
}

fn parse_ascii(path: &Path, text: &str) -> Result<Vec<[[f64; 3]; 3]>, ShapeError> {
    let tokens: Vec<Token> = text
        .lines()
        .enumerate()
        .flat_map(|(n, line)| {
            line.split_whitespace().map(move |word| {
                // split_whitespace yields sub-slices of `line`: the byte offset locates it.
                let byte = word.as_ptr() as usize - line.as_ptr() as usize;
                Token {
                    text: word,
                    line: n + 1,
                    column: line[..byte].chars().count() + 1,
                }
            })
        })
        .collect();
    let end_line = text.lines().count().max(1);
    let fail = |line: usize, column: usize, reason: String| ShapeError::MalformedAscii {
        path: path.to_path_buf(),
        line,
        column,
        reason,
    };
    let mut at = 0usize;
    // The next token, which must be `word` (any word when `word` is empty).
    let mut expect = |word: &str| -> Result<&Token, ShapeError> {
        let t = tokens.get(at).ok_or_else(|| {
            fail(
                end_line,
                1,
                format!("file ends where '{word}' was expected"),
            )
        })?;
        at += 1;
        if word.is_empty() || t.text == word {
            Ok(t)
        } else {
            Err(fail(
                t.line,
                t.column,
                format!("expected '{word}', found '{}'", t.text),
            ))
        }
    };
    let number = |t: &Token| -> Result<f64, ShapeError> {
        match t.text.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(fail(
                t.line,
                t.column,
                format!("'{}' is not a finite number", t.text),
            )),
        }
    };
    let solid_line = expect("solid")?.line;
    let mut triangles = Vec::new();
    // The solid's name is the rest of its line, possibly empty.
    let mut next = expect("")?;
    while next.line == solid_line {
        next = expect("")?;
    }
    loop {
        match next.text {
            "endsolid" => break,
            "facet" => {}
            other => {
                return Err(fail(
                    next.line,
                    next.column,
                    format!("expected 'facet' or 'endsolid', found '{other}'"),
                ))
            }
        }
        expect("normal")?;
        for _ in 0..3 {
            number(expect("")?)?;
        }
        expect("outer")?;
        expect("loop")?;
        let mut tri = [[0.0; 3]; 3];
        for vertex in tri.iter_mut() {
            expect("vertex")?;
            for coord in vertex.iter_mut() {
                *coord = number(expect("")?)?;
            }
        }
        expect("endloop")?;
        expect("endfacet")?;
        triangles.push(tri);
        next = expect("")?;
    }
    Ok(triangles)
}

/// Binary STL bytes of `triangles` (normals from the vertex order), for tests and export.
pub fn binary_stl_bytes(triangles: &[[[f64; 3]; 3]]) -> Vec<u8> {
    let mut out = vec![0u8; BINARY_HEADER_BYTES];
    out[..14].copy_from_slice(b"arachis shapes");
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for tri in triangles {
        for x in unit_normal(tri).iter().chain(tri.iter().flatten()) {
            out.extend_from_slice(&(*x as f32).to_le_bytes());
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// Writes `triangles` (mm) as a binary STL file at `path`, atomically.
pub fn write_binary_stl(path: &Path, triangles: &[[[f64; 3]; 3]]) -> anyhow::Result<()> {
    crate::io::write_atomic(path, |w| {
        w.write_all(&binary_stl_bytes(triangles))?;
        Ok(())
    })
}

/// ASCII STL text of `triangles`, named `name`.
pub fn ascii_stl_text(name: &str, triangles: &[[[f64; 3]; 3]]) -> String {
    let mut out = format!("solid {name}\n");
    for tri in triangles {
        let n = unit_normal(tri);
        out += &format!(
            "  facet normal {:e} {:e} {:e}\n    outer loop\n",
            n[0], n[1], n[2]
        );
        for v in tri {
            out += &format!("      vertex {:e} {:e} {:e}\n", v[0], v[1], v[2]);
        }
        out += "    endloop\n  endfacet\n";
    }
    out + &format!("endsolid {name}\n")
}

fn unit_normal(t: &[[f64; 3]; 3]) -> [f64; 3] {
    let u = [0, 1, 2].map(|a| t[1][a] - t[0][a]);
    let v = [0, 1, 2].map(|a| t[2][a] - t[0][a]);
    let n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 {
        n.map(|x| x / len)
    } else {
        [0.0; 3]
    }
}
