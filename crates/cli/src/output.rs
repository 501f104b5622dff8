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
}
