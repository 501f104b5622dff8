//! The demos' command line: `--screenshot PATH`, `--frames N`, the material choice, and each
//! demo's own flags passed through.

use std::path::PathBuf;

/// The options every demo takes.
#[derive(Debug, Clone, Default)]
pub struct CommonArgs {
    /// Save a screenshot of the window here after `frames` frames, then exit.
    pub screenshot: Option<PathBuf>,
    /// Render this many frames, then exit (with `screenshot`: the frame it captures).
    pub frames: Option<u64>,
}

/// A command-line error: printed with the usage, exit code 2.
#[derive(Debug)]
pub struct ArgError(pub String);

/// The command-line arguments after the program name, split into the common options and the
/// rest (for the demo's own options, in order, as `(flag, value)` pairs). Every option takes
/// one value (`--flag value` or `--flag=value`).
pub fn parse_args(
    args: impl IntoIterator<Item = String>,
    own_flags: &[&str],
) -> Result<(CommonArgs, Vec<(String, String)>), ArgError> {
    let mut common = CommonArgs::default();
    let mut own = Vec::new();
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        if arg == "--help" || arg == "-h" {
            return Err(ArgError(String::new()));
        }
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f.to_string(), Some(v.to_string())),
            _ => (arg.clone(), None),
        };
        if !flag.starts_with("--") {
            return Err(ArgError(format!("unexpected argument `{arg}`")));
        }
        let known = flag == "--screenshot" || flag == "--frames" || own_flags.contains(&&*flag);
        if !known {
            return Err(ArgError(format!("unknown option `{flag}`")));
        }
        let value = match inline {
            Some(v) => v,
            None => it
                .next()
                .ok_or_else(|| ArgError(format!("`{flag}` needs a value")))?,
        };
        match flag.as_str() {
            "--screenshot" => {
                let path = PathBuf::from(&value);
                let ext = path
                    .extension()
                    .and_then(|e| e.to_str())
                    .map(str::to_ascii_lowercase);
                if ext.as_deref() != Some("png") {
                    return Err(ArgError(format!(
                        "--screenshot `{value}`: the file name must end in .png"
                    )));
                }
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
                    && !dir.is_dir()
                {
                    return Err(ArgError(format!(
                        "--screenshot `{value}`: directory `{}` does not exist",
                        dir.display()
                    )));
                }
                common.screenshot = Some(path);
            }
            "--frames" => common.frames = Some(parse_count("--frames", &value, 1, 10_000_000)?),
            _ => own.push((flag, value)),
        }
    }
    if common.screenshot.is_some() && common.frames.is_none() {
        common.frames = Some(60);
    }
    Ok((common, own))
}

/// A whole number in `[lo, hi]`, or an error naming the option.
pub fn parse_count(flag: &str, value: &str, lo: u64, hi: u64) -> Result<u64, ArgError> {
    match value.parse::<u64>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(ArgError(format!(
            "{flag} `{value}`: expected a whole number in [{lo}, {hi}]"
        ))),
    }
}

/// Parses the process's arguments; on error prints it and `usage` and exits with code 2.
pub fn args_or_exit(usage: &str, own_flags: &[&str]) -> (CommonArgs, Vec<(String, String)>) {
    let parsed = parse_args(std::env::args().skip(1), own_flags);
    // The demos open an X11 window (the `render` feature enables winit's X11 backend only):
    // without a display winit would panic, so say what is missing instead.
    if cfg!(target_os = "linux") && parsed.is_ok() && std::env::var_os("DISPLAY").is_none() {
        eprintln!(
            "error: no X display (DISPLAY is not set). Headless: `Xvfb :99 &` and run with \
             DISPLAY=:99 XDG_RUNTIME_DIR=/tmp/xdg (see the README's \"Desktop demos\")"
        );
        std::process::exit(2);
    }
    match parsed {
        Ok(a) => a,
        Err(ArgError(msg)) if msg.is_empty() => {
            println!("{usage}\n{COMMON_USAGE}");
            std::process::exit(0);
        }
        Err(ArgError(msg)) => {
            eprintln!("error: {msg}\n\n{usage}\n{COMMON_USAGE}");
            std::process::exit(2);
        }
    }
}

/// Prints an error about a demo option and exits with code 2.
/// The materials the demos cycle through (`--material`, key M), by name.
pub const MATERIALS: [&str; 3] = ["steel", "glass", "rubber"];

/// creep-law's material `MATERIALS[index]` (G, nu, density of steel, glass, rubber).
pub fn material(index: usize) -> creep_law::Material {
    match index % MATERIALS.len() {
        0 => creep_law::Material::steel(),
        1 => creep_law::Material::glass(),
        _ => creep_law::Material::rubber(),
    }
}

/// The index in [`MATERIALS`] of a `--material` value, or exit 2 with the usage.
pub fn material_arg(usage: &str, value: &str) -> usize {
    MATERIALS
        .iter()
        .position(|m| m == &value)
        .unwrap_or_else(|| {
            exit_with(
                usage,
                &format!("--material `{value}`: expected steel, glass or rubber"),
            )
        })
}

pub fn exit_with(usage: &str, msg: &str) -> ! {
    eprintln!("error: {msg}\n\n{usage}\n{COMMON_USAGE}");
    std::process::exit(2);
}

/// Usage of the common options.
pub const COMMON_USAGE: &str = "common options:
  --screenshot FILE.png   save a screenshot after --frames frames (default 60), then exit
  --frames N              render N frames, then exit (prints the median frame time)
keys: Space pause, . one step while paused, +/- physics steps per frame, R reset, Esc quit;
mouse: left drag orbits the camera, wheel zooms";

#[cfg(test)]
mod tests {
    use super::*;

    fn args(v: &[&str]) -> Result<(CommonArgs, Vec<(String, String)>), ArgError> {
        parse_args(v.iter().map(|s| s.to_string()), &["--spheres"])
    }

    #[test]
    fn parses_and_refuses() {
        let (c, own) = args(&["--frames", "5", "--spheres=10"]).unwrap();
        assert_eq!(c.frames, Some(5));
        assert_eq!(own, vec![("--spheres".to_string(), "10".to_string())]);
        assert!(args(&["--frames", "x"]).is_err());
        assert!(args(&["--frames"]).is_err());
        assert!(args(&["--nope", "1"]).is_err());
        assert!(args(&["--screenshot", "a.jpg"]).is_err());
        assert!(args(&["--screenshot", "/no/such/dir/a.png"]).is_err());
        let (c, _) = args(&["--screenshot", "a.png"]).unwrap();
        assert_eq!(c.frames, Some(60));
    }
}
