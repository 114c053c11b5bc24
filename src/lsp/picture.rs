//! The server's one command, `rayrepl.render`: the document's scene, as
//! evaluated at `time` 0, rendered as the command line renders it, the
//! PNG's bytes (base64, for the client to show) and, if asked, written to a
//! file.

use std::path::PathBuf;

use serde_json::{Value, json};

use super::analysis::Analysis;
use crate::output::write_image;
use crate::pipeline::render_picture;
use crate::presentation;
use crate::render::{Region, RenderControl};
use crate::settings::{DEFAULTS, RenderSettings};

/// The name of the command, as clients call it.
pub(crate) const RENDER: &str = "rayrepl.render";

/// What the client may ask of a render (the second argument of the command).
#[derive(Debug, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Asked {
    width: Option<u32>,
    height: Option<u32>,
    depth: Option<u32>,
    /// A file to write the PNG to, as well.
    output: Option<PathBuf>,
}

/// Renders the scene of `analysis` as `asked` (`null` or an object with
/// `width`, `height`, `depth`, `output`): `{ "width", "height", "png"
/// (base64), "written" (the file, or null) }`, or why it cannot.
pub(crate) fn render_command(analysis: &Analysis, asked: Option<&Value>) -> Result<Value, String> {
    let asked: Asked = match asked {
        None | Some(Value::Null) => Asked::default(),
        Some(value) => {
            serde_json::from_value(value.clone()).map_err(|error| format!("the render's options: {error}"))?
        }
    };
    let Some(interpreter) = analysis.interpreter() else {
        return Err("the scene cannot be rendered: it does not run (see its diagnostics)".to_string());
    };
    if analysis.diagnostics.iter().any(|d| d.severity == crate::lang::Severity::Error) {
        return Err("the scene cannot be rendered: it has an error (see its diagnostics)".to_string());
    }
    let settings = RenderSettings {
        width: asked.width.unwrap_or(DEFAULTS.width),
        height: asked.height.unwrap_or(DEFAULTS.height),
        depth: asked.depth.unwrap_or(DEFAULTS.depth),
        ..DEFAULTS
    };
    settings.validate().map_err(|error| error.to_string())?;
    let options = settings.render_options();
    let whole = Region::whole(&options);
    let image = render_picture(interpreter.scene(), &options, whole, &RenderControl::default())
        .map_err(|error| error.to_string())?
        .image;
    let png = presentation::png(&image).map_err(|error| format!("cannot encode the picture: {error}"))?;
    if let Some(path) = &asked.output {
        write_image(path, &image).map_err(|error| error.to_string())?;
    }
    Ok(json!({
        "width": image.width(),
        "height": image.height(),
        "png": presentation::base64(&png),
        "written": asked.output,
    }))
}
