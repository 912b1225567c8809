//! An OBJ file read line by line for `tobj`, mended on the way: face corners lose the
//! texture-coordinate and normal references that name no `vt` or `vn` defined before the
//! face (`tobj` refuses the whole file for one), and the `usemtl` names are collected. Only
//! one line is held at a time, so loading a file costs its parsed geometry, not copies of
//! its text.
use std::collections::BTreeSet;
use std::io::{BufRead, Read};

/// A mending reader over the lines of `inner`.
pub(crate) struct ObjLines<R> {
    inner: R,
    raw: Vec<u8>,
    line: String,
    at: usize,
    vt: i64,
    vn: i64,
    /// Face corners that lost a reference.
    pub dropped: usize,
    /// Every name `usemtl` gave.
    pub materials: BTreeSet<String>,
}

impl<R: BufRead> ObjLines<R> {
    pub fn new(inner: R) -> Self {
        Self {
            inner,
            raw: Vec::new(),
            line: String::new(),
            at: 0,
            vt: 0,
            vn: 0,
            dropped: 0,
            materials: BTreeSet::new(),
        }
    }

    /// Reads and mends the next line into `self.line` (empty at the end).
    fn next_line(&mut self) -> std::io::Result<()> {
        // The line's bytes leave `self` while the line is mended (and come back for reuse).
        let mut raw = std::mem::take(&mut self.raw);
        raw.clear();
        self.line.clear();
        self.at = 0;
        if self.inner.read_until(b'\n', &mut raw)? > 0 {
            self.mend(&String::from_utf8_lossy(&raw));
        }
        self.raw = raw;
        Ok(())
    }

    /// Mends one line into `self.line`.
    fn mend(&mut self, text: &str) {
        let text = text.trim_end_matches(['\n', '\r']);
        let mut words = text.split_whitespace();
        match words.next() {
            Some("vt") => self.vt += 1,
            Some("vn") => self.vn += 1,
            Some("usemtl") => {
                let name = text.trim_start()["usemtl".len()..].split('#').next();
                if let Some(name) = name.map(str::trim).filter(|n| !n.is_empty()) {
                    self.materials.insert(name.to_string());
                }
            }
            Some("f") => {
                self.line.push('f');
                for corner in words {
                    self.push_corner(corner);
                }
                self.line.push('\n');
                return;
            }
            _ => {}
        }
        self.line.push_str(text);
        self.line.push('\n');
    }

    /// Appends ` v[/vt[/vn]]` of `corner` without references past what is defined so far.
    fn push_corner(&mut self, corner: &str) {
        let valid = |r: &str, count: i64| {
            r.parse::<i64>()
                .is_ok_and(|i| (1..=count).contains(&i) || (-count..=-1).contains(&i))
        };
        let parts: Vec<&str> = corner.split('/').collect();
        let keep = |k: usize, count: i64| {
            parts
                .get(k)
                .copied()
                .filter(|r| r.is_empty() || valid(r, count))
        };
        let (t, n) = (keep(1, self.vt), keep(2, self.vn));
        let lost = (parts.len() > 1 && t.is_none()) || (parts.len() > 2 && n.is_none());
        self.dropped += usize::from(lost);
        self.line.push(' ');
        self.line.push_str(parts[0]);
        match (t.unwrap_or(""), n.unwrap_or("")) {
            ("", "") => {}
            (t, "") => {
                self.line.push('/');
                self.line.push_str(t);
            }
            (t, n) => {
                self.line.push('/');
                self.line.push_str(t);
                self.line.push('/');
                self.line.push_str(n);
            }
        }
    }
}

impl<R: BufRead> Read for ObjLines<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let available = self.fill_buf()?;
        let n = available.len().min(buf.len());
        buf[..n].copy_from_slice(&available[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for ObjLines<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        if self.at >= self.line.len() {
            self.next_line()?;
        }
        Ok(&self.line.as_bytes()[self.at..])
    }

    fn consume(&mut self, amount: usize) {
        self.at = (self.at + amount).min(self.line.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_references_are_dropped_and_materials_named() {
        let text =
            "v 0 0 0\nv 1 0 0\nvt 0 0\nusemtl light # lamp\nf 1/1 2/9 1/-1/4\r\nusemtl floor\n";
        let mut lines = ObjLines::new(text.as_bytes());
        let mut out = String::new();
        lines.read_to_string(&mut out).unwrap();
        assert_eq!(
            out,
            "v 0 0 0\nv 1 0 0\nvt 0 0\nusemtl light # lamp\nf 1/1 2 1/-1\nusemtl floor\n"
        );
        assert_eq!(lines.dropped, 2);
        assert_eq!(
            lines.materials.into_iter().collect::<Vec<_>>(),
            ["floor", "light"]
        );
    }
}
