//! `rayrepl jupyter install`: the kernelspec that lets Jupyter start the
//! kernel (`kernel.json`, and the logos, rendered by the renderer itself).

use std::path::{Path, PathBuf};

use serde_json::json;

use crate::session::{CellSession, Collected, Output, SessionOptions};

/// The kernelspec's name: its folder, and what `jupyter kernelspec list` shows.
pub(crate) const KERNEL_NAME: &str = "rayrepl";

/// What notebooks show as the kernel's name.
pub(crate) const DISPLAY_NAME: &str = "rayrepl (.ray)";

/// Where the kernelspec goes, as `jupyter kernelspec install` says it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum KernelPrefix {
    /// The user's Jupyter data folder (`JUPYTER_DATA_DIR`, else
    /// `~/.local/share/jupyter` on Linux): the default.
    User,
    /// The Python environment Jupyter runs in (`VIRTUAL_ENV` or
    /// `CONDA_PREFIX`, else the prefix `python3` reports).
    SysPrefix,
    /// `PREFIX/share/jupyter`.
    Prefix(PathBuf),
}

/// The scene of the logo: a red ball on a grey floor, as in `hello.ray`.
const LOGO_SCENE: &str = "camera distance 3.2 angle 1 end\n\
    ambient 0.25\n\
    light vector 0.5, 0, 0.5 intensity 0.8 end\n\
    put sphere center 0, 0, 0 radius 1 kd 0.8 ks 0.4 phong 40 color 220, 40, 40 end\n\
    put plane rotation 0, 0, 0 shift -1 kd 0.8 ks 0.2 phong 10 color 90, 90, 110 end";

/// Writes the kernelspec under `prefix`, starting `program` (this
/// program's path) with the interrupt mode `interrupt_mode` (`message` or
/// `signal`); gives the folder written.
pub fn install(prefix: &KernelPrefix, program: &Path, interrupt_mode: &str) -> Result<PathBuf, String> {
    let folder = kernels_folder(prefix)?.join(KERNEL_NAME);
    std::fs::create_dir_all(&folder)
        .map_err(|error| format!("{} cannot be made: {}", folder.display(), crate::output::io_reason(&error)))?;
    let spec = json!({
        "argv": [program, "jupyter", "--connection-file", "{connection_file}"],
        "display_name": DISPLAY_NAME,
        "language": super::LANGUAGE,
        "interrupt_mode": interrupt_mode,
        "metadata": { "debugger": false },
    });
    let mut text = serde_json::to_string_pretty(&spec).expect("a JSON value always prints");
    text.push('\n');
    write(&folder.join("kernel.json"), text.as_bytes())?;
    for size in [32, 64] {
        write(&folder.join(format!("logo-{size}x{size}.png")), &logo(size))?;
    }
    Ok(folder)
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    std::fs::write(path, bytes)
        .map_err(|error| format!("{} cannot be written: {}", path.display(), crate::output::io_reason(&error)))
}

/// The `kernels` folder of Jupyter's data folder under `prefix`.
fn kernels_folder(prefix: &KernelPrefix) -> Result<PathBuf, String> {
    let data = match prefix {
        KernelPrefix::User => match std::env::var_os("JUPYTER_DATA_DIR") {
            Some(folder) => PathBuf::from(folder),
            None => jupyter_zmq_client::dirs::user_data_dir()
                .map_err(|error| format!("the user's Jupyter folder is not known: {error}"))?,
        },
        KernelPrefix::SysPrefix => python_prefix()?.join("share").join("jupyter"),
        KernelPrefix::Prefix(prefix) => prefix.join("share").join("jupyter"),
    };
    Ok(data.join("kernels"))
}

/// The prefix of the Python environment Jupyter runs in.
fn python_prefix() -> Result<PathBuf, String> {
    for variable in ["VIRTUAL_ENV", "CONDA_PREFIX"] {
        if let Some(prefix) = std::env::var_os(variable).filter(|prefix| !prefix.is_empty()) {
            return Ok(PathBuf::from(prefix));
        }
    }
    let asked = std::process::Command::new("python3").args(["-c", "import sys; print(sys.prefix)"]).output();
    match asked {
        Ok(output) if output.status.success() => Ok(PathBuf::from(String::from_utf8_lossy(&output.stdout).trim())),
        _ => Err("--sys-prefix needs the Python environment: activate it, or give --prefix".to_string()),
    }
}

/// The logo, `size` pixels square, as PNG.
fn logo(size: u32) -> Vec<u8> {
    let mut cells = CellSession::new(&SessionOptions::default());
    let mut shown = Collected::default();
    cells.run("<logo>", &format!(":size {size} {size}\n{LOGO_SCENE}\n:render"), &mut shown);
    let mut png = Vec::new();
    if let Some(Output::Picture(picture)) = shown.outputs.iter().find(|output| matches!(output, Output::Picture(_))) {
        crate::output::write_png(&mut png, &picture.image).expect("a PNG is always encoded in memory");
    }
    png
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_kernelspec_starts_this_program_with_the_connection_file() {
        let prefix = tempfile::tempdir().expect("a temporary folder");
        let program = Path::new("/opt/bin/rayrepl");
        let folder = install(&KernelPrefix::Prefix(prefix.path().to_path_buf()), program, "message").expect("written");
        assert_eq!(folder, prefix.path().join("share/jupyter/kernels/rayrepl"));
        let spec: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(folder.join("kernel.json")).expect("read")).expect("JSON");
        assert_eq!(spec["argv"], json!(["/opt/bin/rayrepl", "jupyter", "--connection-file", "{connection_file}"]));
        assert_eq!((spec["display_name"].as_str(), spec["language"].as_str()), (Some(DISPLAY_NAME), Some("ray")));
        let logo = image::open(folder.join("logo-64x64.png")).expect("a PNG").to_rgb8();
        assert_eq!(logo.dimensions(), (64, 64));
        let centre = logo.get_pixel(32, 32).0;
        assert!(centre[0] > 2 * centre[1], "the ball is red in the middle: {centre:?}");
    }
}
