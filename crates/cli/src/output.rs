//! The CLI's output files: the directory a command writes into and the text files (CSV,
//! Markdown) in it, every failure carrying the path it concerns.

use std::path::{Path, PathBuf};

/// A file or directory could not be written.
#[derive(Debug, thiserror::Error)]
#[error("writing {path}: {source}")]
pub struct OutputError {
    /// The file or directory.
    pub path: PathBuf,
    /// The system's error.
    pub source: std::io::Error,
}

/// Creates the output directory `dir` (and its parents) if it does not exist.
pub fn create_dir(dir: &Path) -> Result<(), OutputError> {
    std::fs::create_dir_all(dir).map_err(|source| OutputError {
        path: dir.to_path_buf(),
        source,
    })
}

/// Writes `text` to the file `path`, replacing it.
pub fn write(path: &Path, text: &str) -> Result<(), OutputError> {
    std::fs::write(path, text).map_err(|source| OutputError {
        path: path.to_path_buf(),
        source,
    })
}

/// A CSV table (RFC 4180) built in memory: a header, then rows of as many fields, each written
/// with its own `Display` (so a caller keeps its number formats); a field holding a comma, a
/// quote or a line break is quoted. The CLI's one way of writing CSV.
#[derive(Debug, Clone)]
pub struct Csv {
    text: String,
    columns: usize,
}

impl Csv {
    /// A table with these column names.
    pub fn new(header: &[&str]) -> Self {
        let mut t = Self {
            text: String::new(),
            columns: header.len(),
        };
        let fields: Vec<&dyn std::fmt::Display> =
            header.iter().map(|h| h as &dyn std::fmt::Display).collect();
        t.push(&fields);
        t
    }

    /// Appends one row; it must have as many fields as the header (a programming error
    /// otherwise, caught in debug builds).
    pub fn row(&mut self, fields: &[&dyn std::fmt::Display]) {
        debug_assert_eq!(fields.len(), self.columns, "CSV row width");
        self.push(fields);
    }

    fn push(&mut self, fields: &[&dyn std::fmt::Display]) {
        push_row(&mut self.text, fields);
    }

    /// Writes the table to `path`.
    pub fn write(&self, path: &Path) -> Result<(), OutputError> {
        write(path, &self.text)
    }
}

/// One CSV row (RFC 4180 quoting, see [`Csv`]) appended to `text`, with its line break.
fn push_row(text: &mut String, fields: &[&dyn std::fmt::Display]) {
    use std::fmt::Write as _;
    for (i, f) in fields.iter().enumerate() {
        if i > 0 {
            text.push(',');
        }
        let start = text.len();
        // Writing into a String cannot fail.
        let _ = write!(text, "{f}");
        if text[start..].contains([',', '"', '\n', '\r']) {
            let quoted = format!("\"{}\"", text[start..].replace('"', "\"\""));
            text.truncate(start);
            text.push_str(&quoted);
        }
    }
    text.push('\n');
}

/// The same CSV rows as [`Csv`], streamed to a writer (the commands that print CSV on stdout
/// row by row as they compute): the header on creation, then one row a call.
pub struct CsvWriter<'a> {
    out: &'a mut dyn std::io::Write,
    columns: usize,
    line: String,
}

impl<'a> CsvWriter<'a> {
    /// Writes the header `header` to `out`.
    pub fn new(out: &'a mut dyn std::io::Write, header: &[&str]) -> std::io::Result<Self> {
        let mut w = Self {
            out,
            columns: header.len(),
            line: String::new(),
        };
        let fields: Vec<&dyn std::fmt::Display> =
            header.iter().map(|h| h as &dyn std::fmt::Display).collect();
        w.emit(&fields)?;
        Ok(w)
    }

    /// Writes one row; it must have as many fields as the header (a programming error
    /// otherwise, caught in debug builds).
    pub fn row(&mut self, fields: &[&dyn std::fmt::Display]) -> std::io::Result<()> {
        debug_assert_eq!(fields.len(), self.columns, "CSV row width");
        self.emit(fields)
    }

    /// A line that is not a row (a `#` comment), passed through as it is.
    pub fn comment(&mut self, text: &str) -> std::io::Result<()> {
        writeln!(self.out, "# {text}")
    }

    /// Flushes the writer (rows printed so far become visible).
    pub fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }

    fn emit(&mut self, fields: &[&dyn std::fmt::Display]) -> std::io::Result<()> {
        self.line.clear();
        push_row(&mut self.line, fields);
        self.out.write_all(self.line.as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_path() {
        let dir = std::env::temp_dir().join(format!("creep-output-{}", std::process::id()));
        create_dir(&dir.join("a/b")).unwrap();
        write(&dir.join("a/b/x.csv"), "x\n1\n").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.join("a/b/x.csv")).unwrap(),
            "x\n1\n"
        );
        // A file where a directory is expected.
        let e = write(&dir.join("a/b/x.csv/y.csv"), "").unwrap_err();
        assert!(e.to_string().contains("x.csv/y.csv"), "{e}");
        let e = create_dir(&dir.join("a/b/x.csv/sub")).unwrap_err();
        assert!(e.to_string().contains("x.csv/sub"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn csv_rows_keep_formats_and_quote_separators() {
        let mut t = Csv::new(&["name", "value"]);
        t.row(&[&"plain", &format_args!("{:.3}", 1.23456)]);
        t.row(&[&"a, b", &"say \"hi\""]);
        assert_eq!(
            t.text,
            "name,value\nplain,1.235\n\"a, b\",\"say \"\"hi\"\"\"\n"
        );
        // The streamed writer gives the same bytes.
        let mut buf = Vec::new();
        let mut w = CsvWriter::new(&mut buf, &["name", "value"]).unwrap();
        w.row(&[&"plain", &format_args!("{:.3}", 1.23456)]).unwrap();
        w.row(&[&"a, b", &"say \"hi\""]).unwrap();
        assert_eq!(String::from_utf8(buf).unwrap(), t.text);
    }
}
