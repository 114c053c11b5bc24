//! rayrepl's session core for the browser: a [`Playground`] holds one
//! [`CellSession`] and runs text in it, as cells of a notebook are run,
//! handing back what the session showed as a [`Reply`]: its outputs as
//! JSON (text with its role, diagnostics drawn as the terminal draws them
//! and as data, pixel explanations, lesson steps and verdicts) and its
//! pictures as bytes, both as `rayrepl::presentation` makes them for the
//! notebook kernel too. The page (`web/src/`) and the Node test
//! (`web/test/node.mjs`) call it from JavaScript through wasm-bindgen; the
//! renderer, the language and the commands are the library's, unchanged,
//! so the pixels are the bytes the command line writes.

use std::path::Path;
use std::time::Duration;

use image::RgbImage;
use rayrepl::lang::{Limits, SourceMap};
use rayrepl::presentation::{apng, outputs_json, pictures, png};
use rayrepl::session::{CellEnd, CellSession, Collected, FrontEnd, Output, RenderSettings, SessionOptions, TextRole};
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// The page's clock: milliseconds since the page (or worker) started.
    #[wasm_bindgen(js_namespace = performance)]
    fn now() -> f64;

    /// Writes a line to the browser's console.
    #[wasm_bindgen(js_namespace = console)]
    fn error(message: &str);
}

/// The browser's clock, for the durations the session reports (a render's
/// time); the standard library has none on `wasm32-unknown-unknown`.
fn browser_clock() -> Duration {
    Duration::from_secs_f64(now() / 1000.0)
}

/// Sets up what the library needs from the browser, once, when the module
/// is instantiated: its clock, and a panic's message on the console (the
/// page then sees the module trap, and starts a new worker).
#[wasm_bindgen(start)]
pub fn start() {
    rayrepl::clock::supply_clock(browser_clock);
    std::panic::set_hook(Box::new(|info| error(&format!("rayrepl panicked: {info}"))));
}

/// The deepest chain of procedure calls in the browser. A worker's stack
/// (V8's, about 1 MB, which WebAssembly cannot grow) holds about 1,500 of
/// the interpreter's calls, where the command line's grows to its 100,000
/// (`stacker`); past this limit a scene gets the diagnostic the command
/// line gives with `--max-calls 1000`, not a trap.
const BROWSER_CALL_DEPTH: usize = 1_000;

/// The settings a playground starts with, as the page's controls give them.
#[wasm_bindgen]
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Width of the picture in pixels.
    pub width: u32,
    /// Height of the picture in pixels.
    pub height: u32,
    /// Reflections followed.
    pub depth: u32,
    /// Rays per pixel.
    pub samples: u32,
    /// The value of `time`.
    pub time: f64,
}

#[wasm_bindgen]
impl Settings {
    /// The command line's defaults (800x600, depth 5, one ray a pixel, time 0).
    #[wasm_bindgen(constructor)]
    pub fn new() -> Settings {
        let defaults = RenderSettings::default();
        Settings {
            width: defaults.width,
            height: defaults.height,
            depth: defaults.depth,
            samples: defaults.samples,
            time: defaults.time,
        }
    }
}

impl Default for Settings {
    fn default() -> Settings {
        Settings::new()
    }
}

/// One session of the language, driven by the page.
#[wasm_bindgen]
pub struct Playground {
    session: CellSession,
    /// How many cells have run, to name the next one's diagnostics.
    cells: usize,
}

#[wasm_bindgen]
impl Playground {
    /// A session with `settings`, checked against the command line's
    /// limits (a refusal says which and why), with the command line's
    /// limit on primitives and [`BROWSER_CALL_DEPTH`] calls.
    #[wasm_bindgen(constructor)]
    pub fn new(settings: &Settings) -> Result<Playground, JsError> {
        let settings = RenderSettings {
            width: settings.width,
            height: settings.height,
            depth: settings.depth,
            samples: settings.samples,
            time: settings.time,
            ..RenderSettings::default()
        };
        settings.validate().map_err(|refusal| JsError::new(&refusal.to_string()))?;
        let limits = Limits { max_call_depth: BROWSER_CALL_DEPTH, ..Limits::DEFAULT };
        let options = SessionOptions { settings, limits, ..SessionOptions::default() };
        Ok(Playground { session: CellSession::new(&options), cells: 0 })
    }

    /// Runs `text` as a cell: items and `:` commands, stopping at the
    /// first error; its diagnostics name it `<cell N>`.
    pub fn run(&mut self, text: &str) -> Reply {
        self.run_as("cell", text, CellSession::run)
    }

    /// Runs `text` as the whole of the learner's scene, in place of the
    /// session's program, and checks the lesson followed once, after it
    /// (`CellSession::run_scene`): a pause in typing is one try of the
    /// step, however many inputs the scene holds. Its diagnostics name it
    /// `<scene N>`.
    pub fn run_scene(&mut self, text: &str) -> Reply {
        self.run_as("scene", text, CellSession::run_scene)
    }

    /// Rows `top..bottom` of the picture `:render` makes of the session's
    /// scene, as RGBA bytes (the reply's `band`, see [`rgba_of`]), with the
    /// notes `:render` gives: the page renders the bands of one picture in
    /// several workers, each with a playground loaded with the same scene
    /// and settings, and puts them together on its canvas. When the memory
    /// the render needs cannot be had, the reply fails and says so.
    pub fn render_rows(&mut self, top: u32, bottom: u32) -> Reply {
        let mut front = Collected::default();
        let (end, band) = match self.session.render_rows(top..bottom, &mut front) {
            Ok(band) => (CellEnd::Done, rgba_of(&band)),
            Err(refusal) => {
                front.outputs.push(Output::Text { role: TextRole::Error, text: refusal.to_string() });
                (CellEnd::Failed, Vec::new())
            }
        };
        Reply { band, ..Reply::new(end, front.outputs, self.session.sources()) }
    }

    /// Makes the picture of `width` x `height` pixels whose RGBA bytes are
    /// `rgba` (the bands the page put together) the session's last
    /// picture, as `:render` would have made it, so that `:pick` explains
    /// its pixels without rendering it again.
    pub fn adopt_picture(&mut self, width: u32, height: u32, rgba: &[u8]) -> Result<(), JsError> {
        self.session.adopt_picture(rgb_of(width, height, rgba)?);
        Ok(())
    }

    /// Runs `text` as the scene file `name` (`scene.ray`), as `:load`
    /// would run it: the whole file, its camera first.
    pub fn load(&mut self, name: &str, text: &str) -> Reply {
        let mut front = Collected::default();
        let end = self.session.load_text(Path::new(name), text, &mut front);
        Reply::new(end, front.outputs, self.session.sources())
    }
}

impl Playground {
    /// Runs `text` with `run`, named `<NOUN N>` (N counting what has run),
    /// and gives what it showed.
    fn run_as(
        &mut self,
        noun: &str,
        text: &str,
        run: fn(&mut CellSession, &str, &str, &mut dyn FrontEnd) -> CellEnd,
    ) -> Reply {
        self.cells += 1;
        let name = format!("<{noun} {}>", self.cells);
        let mut front = Collected::default();
        let end = run(&mut self.session, &name, text, &mut front);
        Reply::new(end, front.outputs, self.session.sources())
    }
}

/// What a cell showed: its outputs in order, with their pictures.
#[wasm_bindgen]
pub struct Reply {
    /// How the cell ended: `done`, `failed`, `interrupted` or `quit`.
    end: &'static str,
    /// The outputs as JSON (`rayrepl::presentation::outputs_json`).
    json: String,
    /// The outputs, which hold the pictures the JSON numbers.
    outputs: Vec<Output>,
    /// The RGBA bytes of the rows [`Playground::render_rows`] rendered;
    /// empty in the reply of anything else.
    band: Vec<u8>,
}

#[wasm_bindgen]
impl Reply {
    /// How the cell ended: `done`, `failed`, `interrupted` or `quit`.
    #[wasm_bindgen(getter)]
    pub fn end(&self) -> String {
        self.end.to_string()
    }

    /// The outputs, as a JSON list of objects with a `kind`
    /// (`rayrepl::presentation::outputs_json` gives each kind).
    #[wasm_bindgen(getter)]
    pub fn outputs(&self) -> String {
        self.json.clone()
    }

    /// The RGBA bytes of the rows [`Playground::render_rows`] rendered
    /// (empty in the reply of anything else), handed over: a second call
    /// gives none.
    pub fn band(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.band)
    }

    /// Picture `index` as RGBA bytes, the canvas's `ImageData`: the RGB
    /// bytes the batch renderer writes, each pixel opaque.
    pub fn rgba(&self, index: usize) -> Result<Vec<u8>, JsError> {
        Ok(rgba_of(self.picture(index)?))
    }

    /// The animation `:play N FPS` showed as an APNG file, the bytes
    /// `rayrepl --anim N --fps FPS -o out.apng` writes; empty without one.
    pub fn apng(&self) -> Result<Vec<u8>, JsError> {
        let played = self.outputs.iter().find_map(|output| match output {
            Output::Frames { frames, fps } => Some((frames, *fps)),
            _ => None,
        });
        let Some((frames, fps)) = played else { return Ok(Vec::new()) };
        apng(frames, fps).map_err(|e| JsError::new(&e.to_string()))
    }

    /// Picture `index` as a PNG file, the bytes `rayrepl -o out.png` writes.
    pub fn png(&self, index: usize) -> Result<Vec<u8>, JsError> {
        png_bytes(self.picture(index)?)
    }
}

impl Reply {
    /// Picture `index` as the JSON numbers it, or the error JavaScript
    /// sees for one the reply does not have.
    fn picture(&self, index: usize) -> Result<&RgbImage, JsError> {
        let mut all = self.outputs.iter().flat_map(pictures);
        all.nth(index).ok_or_else(|| JsError::new(&format!("the reply has no picture {index}")))
    }

    /// The reply of a cell that ended with `end` after showing `outputs`,
    /// its diagnostics pointing into `sources`.
    fn new(end: CellEnd, outputs: Vec<Output>, sources: &SourceMap) -> Reply {
        let end = match end {
            CellEnd::Done => "done",
            CellEnd::Failed => "failed",
            CellEnd::Interrupted => "interrupted",
            CellEnd::Quit => "quit",
        };
        Reply { end, json: outputs_json(&outputs, sources), outputs, band: Vec::new() }
    }
}

/// `image` as RGBA bytes, the canvas's `ImageData`: the RGB bytes the
/// batch renderer writes, each pixel opaque.
fn rgba_of(image: &RgbImage) -> Vec<u8> {
    image.pixels().flat_map(|pixel| [pixel[0], pixel[1], pixel[2], u8::MAX]).collect()
}

/// The PNG file of the picture of `width` x `height` pixels whose RGBA
/// bytes are `rgba` (the bands the page put together), the bytes
/// `rayrepl -o out.png` writes of it (the alpha bytes are left out).
#[wasm_bindgen]
pub fn png_of_rgba(width: u32, height: u32, rgba: &[u8]) -> Result<Vec<u8>, JsError> {
    png_bytes(&rgb_of(width, height, rgba)?)
}

/// The picture of `width` x `height` pixels whose RGBA bytes are `rgba`
/// (the alpha bytes left out).
fn rgb_of(width: u32, height: u32, rgba: &[u8]) -> Result<RgbImage, JsError> {
    let rgb = rgba.chunks_exact(4).flat_map(|pixel| [pixel[0], pixel[1], pixel[2]]).collect();
    RgbImage::from_raw(width, height, rgb).ok_or_else(|| JsError::new("the bytes are not a picture of that size"))
}

/// `image` as a PNG file, the bytes `rayrepl -o out.png` writes.
fn png_bytes(image: &RgbImage) -> Result<Vec<u8>, JsError> {
    png(image).map_err(|e| JsError::new(&e.to_string()))
}
