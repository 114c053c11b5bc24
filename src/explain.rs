//! "Why is this pixel this colour?": the paths traced for a pixel
//! ([`crate::render::pixel_paths`]) told with the program's own places, in
//! words for a person and as one JSON object for tools.
//!
//! Each surface met is named by its kind and the `put` that placed it,
//! with the chain of procedure calls (and their argument values) that led
//! to that `put`; each light is lit (its diffuse and specular parts),
//! facing away, or in the shadow of a named object; each level's colour is
//! the clamped sum, down to the bytes written.

use std::fmt::Write as _;

use glam::DVec3;
use serde_json::{Map, Value, json};

use crate::lang::eval::{Call, Origins};
use crate::lang::number::format_number;
use crate::lang::{Interpreter, SourceMap, Span};
use crate::render::pixel_paths::{LEVELS_RECORDED, Level, LightPart, SAMPLES_RECORDED, SamplePath, Surface};
use crate::render::{Explainer, PixelPaths, RenderOptions};
use crate::scene::{Scene, Shape};

/// At most this many calls of a chain are written out in words (a deep
/// recursion would fill the screen); the JSON has them all.
const CALLS_SHOWN: usize = 8;

/// The explanation of one pixel: its paths and where their parts come from.
pub struct Explanation<'a> {
    /// What was traced.
    pub paths: PixelPaths,
    scene: &'a Scene,
    origins: &'a Origins,
    sources: &'a SourceMap,
}

/// A scene evaluated with the calls of each `put` recorded, ready to
/// explain its pixels.
pub struct ExplainedScene<'a> {
    explainer: Explainer<'a>,
    scene: &'a Scene,
    origins: &'a Origins,
    sources: &'a SourceMap,
}

impl<'a> ExplainedScene<'a> {
    /// Prepares to explain the pixels of the scene that `interpreter` built
    /// (with [`Interpreter::recording_calls`], for the call chains) from
    /// the texts of `sources`, rendered with `options`.
    pub fn new(interpreter: &'a Interpreter, sources: &'a SourceMap, options: &RenderOptions) -> ExplainedScene<'a> {
        let scene = interpreter.scene();
        ExplainedScene { explainer: Explainer::new(scene, options), scene, origins: interpreter.origins(), sources }
    }

    /// Explains pixel `(x, y)` (from the left and from the top).
    ///
    /// # Panics
    ///
    /// If the pixel is outside the image.
    pub fn explain(&self, x: u32, y: u32) -> Explanation<'a> {
        Explanation {
            paths: self.explainer.explain(x, y),
            scene: self.scene,
            origins: self.origins,
            sources: self.sources,
        }
    }
}

/// A place in the sources: file, line and column.
struct Place<'s> {
    file: &'s str,
    line: usize,
    column: usize,
}

impl Explanation<'_> {
    /// The explanation as one JSON object: `pixel`, `rgb` (the bytes
    /// written), `color` (the average before rounding), `path` (the first
    /// sample's surfaces, camera ray first) and, with several samples,
    /// `samples` (each recorded one's `color` and `path`). What was traced
    /// but not recorded is counted: `more_reflections` beside a path cut
    /// short, `more_samples` (how many, their average `color`), and a `note`
    /// saying so.
    pub fn to_json(&self) -> Value {
        let (x, y) = self.paths.pixel;
        let samples = &self.paths.samples;
        let mut object = Map::new();
        object.insert("pixel".into(), json!([x, y]));
        object.insert("rgb".into(), json!(self.paths.rgb));
        object.insert("color".into(), triple(self.paths.colour));
        object.insert("path".into(), samples.first().map_or(json!([]), |path| self.path_json(path)));
        if let Some(more) = samples.first().map(|path| path.unrecorded_levels).filter(|&more| more > 0) {
            object.insert("more_reflections".into(), json!(more));
        }
        if self.paths.traced > 1 {
            let each = samples.iter().map(|path| {
                let mut sample = Map::new();
                sample.insert("color".into(), triple(path.colour()));
                sample.insert("path".into(), self.path_json(path));
                if path.unrecorded_levels > 0 {
                    sample.insert("more_reflections".into(), json!(path.unrecorded_levels));
                }
                Value::Object(sample)
            });
            object.insert("samples".into(), Value::Array(each.collect()));
        }
        if self.paths.unrecorded() > 0 {
            let more = json!({"count": self.paths.unrecorded(), "color": triple(self.paths.unrecorded_colour)});
            object.insert("more_samples".into(), more);
        }
        if let Some(note) = self.note() {
            object.insert("note".into(), json!(note));
        }
        Value::Object(object)
    }

    /// What was traced but not recorded, if anything was.
    fn note(&self) -> Option<String> {
        let cut_paths = self.paths.samples.iter().any(|path| path.unrecorded_levels > 0);
        let cut_samples = self.paths.unrecorded() > 0;
        let what = match (cut_samples, cut_paths) {
            (false, false) => return None,
            (true, false) => format!("the paths of the first {SAMPLES_RECORDED} samples"),
            (false, true) => format!("the first {LEVELS_RECORDED} rays of each path"),
            (true, true) => {
                format!("the paths of the first {SAMPLES_RECORDED} samples, each to its first {LEVELS_RECORDED} rays,")
            }
        };
        Some(format!(
            "only {what} are shown: every sample was traced down to the depth, and the colour and the bytes count them all"
        ))
    }

    fn path_json(&self, path: &SamplePath) -> Value {
        Value::Array(path.levels.iter().map(|level| self.level_json(level)).collect())
    }

    fn level_json(&self, level: &Level) -> Value {
        let Some(surface) = &level.surface else {
            return json!({"object": null, "weight": level.weight, "color": triple(level.colour)});
        };
        let material = surface.material;
        let lights: Vec<Value> = level.lights.iter().enumerate().map(|(j, part)| self.light_json(j, part)).collect();
        json!({
            "object": self.object_json(surface.primitive),
            "point": triple(surface.point),
            "normal": triple(surface.normal),
            "weight": level.weight,
            "texture": {"kd": material.kd, "ks": material.ks, "phong": material.phong, "color": triple(material.color)},
            "ambient": triple(level.ambient),
            "lights": lights,
            "ks": material.ks,
            "color": triple(level.colour),
        })
    }

    fn light_json(&self, index: usize, part: &LightPart) -> Value {
        let mut light = Map::new();
        light.insert("light".into(), json!(index + 1));
        if let Some(place) = self.origins.lights.get(index).map(|origin| self.place(origin.item)) {
            insert_place(&mut light, &place);
        }
        let (state, diffuse, specular) = match part {
            LightPart::Lit { diffuse, specular } => ("lit", *diffuse, *specular),
            LightPart::FacingAway => ("facing away", DVec3::ZERO, DVec3::ZERO),
            LightPart::Shadowed(_) => ("shadowed", DVec3::ZERO, DVec3::ZERO),
        };
        light.insert("state".into(), json!(state));
        light.insert("diffuse".into(), triple(diffuse));
        light.insert("specular".into(), triple(specular));
        if let LightPart::Shadowed(blocker) = part {
            light.insert("blocker".into(), blocker.map_or(Value::Null, |primitive| self.object_json(primitive)));
        }
        Value::Object(light)
    }

    /// `{"kind", "file", "line", "column", "calls"}` of a primitive.
    fn object_json(&self, primitive: usize) -> Value {
        let mut object = Map::new();
        object.insert("kind".into(), json!(self.kind(primitive)));
        if let Some(put) = self.put(primitive) {
            insert_place(&mut object, &self.place(put));
        }
        let calls = self.calls(primitive).into_iter().map(|call| {
            let arguments: Map<String, Value> =
                call.arguments.iter().map(|(name, value)| (name.to_string(), json!(value))).collect();
            let mut entry = Map::new();
            entry.insert("proc".into(), json!(&*call.procedure));
            entry.insert("args".into(), Value::Object(arguments));
            insert_place(&mut entry, &self.place(call.span));
            Value::Object(entry)
        });
        object.insert("calls".into(), Value::Array(calls.collect()));
        Value::Object(object)
    }

    /// `sphere`, `plane` or `box`.
    fn kind(&self, primitive: usize) -> &'static str {
        let scene = self.scene;
        let found = match primitive.checked_sub(scene.primitives.len()) {
            None => scene.primitives.get(primitive),
            Some(timed) => scene.timed_primitives.get(timed),
        };
        match found.map(|p| p.shape) {
            Some(Shape::Sphere { .. }) => "sphere",
            Some(Shape::Plane { .. }) => "plane",
            Some(Shape::Box { .. }) => "box",
            None => "object",
        }
    }

    /// The `put` that placed a primitive.
    fn put(&self, primitive: usize) -> Option<Span> {
        self.origins.put_of(primitive, self.scene.primitives.len())
    }

    /// The calls that led to a primitive's `put`, innermost first.
    fn calls(&self, primitive: usize) -> Vec<&Call> {
        self.origins.calls_of(primitive, self.scene.primitives.len())
    }

    fn place(&self, span: Span) -> Place<'_> {
        let file = self.sources.get(span.source);
        let (line, column) = file.line_col(span.start as usize);
        Place { file: &file.name, line, column }
    }

    /// The text of the line where `span` starts, trimmed.
    fn source_line(&self, span: Span) -> &str {
        let text = &self.sources.get(span.source).text;
        let start = (span.start as usize).min(text.len());
        let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
        let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
        text[line_start..line_end].trim()
    }
}

impl std::fmt::Display for Explanation<'_> {
    /// The explanation in words: each recorded sample's path, level by
    /// level, what was traced but not recorded, then the bytes.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (x, y) = self.paths.pixel;
        let (samples, traced) = (&self.paths.samples, self.paths.traced);
        writeln!(f, "pixel ({x}, {y})")?;
        for (k, path) in samples.iter().enumerate() {
            if traced > 1 {
                writeln!(f, "sample {} of {traced}: colour {}", k + 1, colour(path.colour()))?;
            }
            for (depth, level) in path.levels.iter().enumerate() {
                let last = depth + 1 == path.levels.len() && path.unrecorded_levels == 0;
                f.write_str(&self.level_text(depth, level, last))?;
            }
            if path.unrecorded_levels > 0 {
                let indent = "  ".repeat(path.levels.len());
                let more = more(path.unrecorded_levels, "reflection", "reflections");
                writeln!(f, "{indent}... and {more}, traced but not shown")?;
            }
        }
        let unrecorded = self.paths.unrecorded();
        if unrecorded > 0 {
            let (first, average) = (samples.len() + 1, colour(self.paths.unrecorded_colour));
            let more = more(unrecorded, "sample", "samples");
            writeln!(f, "... and {more} ({first} to {traced}), traced but not shown: their average colour {average}")?;
        }
        if let Some(note) = self.note() {
            writeln!(f, "note: {note}")?;
        }
        let [r, g, b] = self.paths.rgb;
        let mean = if traced > 1 { format!("the average of {traced} samples, ") } else { String::new() };
        writeln!(f, "rgb ({r}, {g}, {b}) = round(255 × {mean}{})", colour(self.paths.colour))
    }
}

impl Explanation<'_> {
    /// One level of a path in words, indented by its depth; `last` when no
    /// ray was followed from it.
    fn level_text(&self, depth: usize, level: &Level, last: bool) -> String {
        let indent = "  ".repeat(depth);
        let ray = if depth == 0 {
            "the camera ray".to_string()
        } else {
            format!("the reflected ray (weight {})", short(level.weight))
        };
        let Some(surface) = &level.surface else {
            let what = if depth == 0 { "nothing: background, black" } else { "nothing: black" };
            return format!("{indent}{ray} met {what}\n");
        };
        let mut text = format!("{indent}{ray} met {}\n", self.object_text(surface.primitive, &indent));
        let more = format!("{indent}    ");
        let _ = writeln!(text, "{more}ambient      {}", colour(level.ambient));
        for (j, part) in level.lights.iter().enumerate() {
            let light = match self.origins.lights.get(j) {
                Some(origin) => format!("light {} ({})", j + 1, self.place_text(origin.item)),
                None => format!("light {}", j + 1),
            };
            let state = match part {
                LightPart::Lit { diffuse, specular } => {
                    format!("lit: diffuse {}, specular {}", colour(*diffuse), colour(*specular))
                }
                LightPart::FacingAway => "facing away from the surface: nothing".to_string(),
                LightPart::Shadowed(Some(blocker)) => format!("in the shadow of {}", self.object_place(*blocker)),
                LightPart::Shadowed(None) => "in shadow: nothing".to_string(),
            };
            let _ = writeln!(text, "{more}{light}: {state}");
        }
        let _ = writeln!(text, "{more}{}", self.sum_text(surface, level, last));
        text
    }

    /// "colour = clamp(...) = (r, g, b)": how the level's colour is made;
    /// `last` when no reflected ray was followed from it.
    fn sum_text(&self, surface: &Surface, level: &Level, last: bool) -> String {
        let ks = surface.material.ks;
        let (reflected, dropped) = match (ks == 0.0, last) {
            (true, _) => (String::new(), ""),
            (false, false) => (format!(" + {} × reflected", short(ks)), ""),
            (false, true) => (String::new(), " (the depth is reached: no reflection)"),
        };
        format!("colour = clamp(ambient + lights{reflected}) = {}{dropped}", colour(level.colour))
    }

    /// "a sphere put at scene.ray:4:1".
    fn object_place(&self, primitive: usize) -> String {
        let kind = self.kind(primitive);
        let article = if kind == "object" { "an" } else { "a" };
        match self.put(primitive) {
            Some(put) => format!("{article} {kind} put at {}", self.place_text(put)),
            None => format!("{article} {kind}"),
        }
    }

    /// "a sphere put at scene.ray:4:1  `put sphere ...`", then the calls
    /// that led to that `put`, one a line under `indent`.
    fn object_text(&self, primitive: usize, indent: &str) -> String {
        let mut text = self.object_place(primitive);
        let Some(put) = self.put(primitive) else { return text };
        let _ = write!(text, "  `{}`", self.source_line(put));
        let calls = self.calls(primitive);
        for call in calls.iter().take(CALLS_SHOWN) {
            let arguments: Vec<String> =
                call.arguments.iter().map(|(name, value)| format!("{name} = {}", format_number(*value))).collect();
            let _ = write!(
                text,
                "\n{indent}    in {}({}) called at {}",
                call.procedure,
                arguments.join(", "),
                self.place_text(call.span)
            );
        }
        if calls.len() > CALLS_SHOWN {
            let _ = write!(text, "\n{indent}    ... and {} calls more", calls.len() - CALLS_SHOWN);
        }
        text
    }

    /// "scene.ray:4:1".
    fn place_text(&self, span: Span) -> String {
        let place = self.place(span);
        format!("{}:{}:{}", place.file, place.line, place.column)
    }
}

/// Adds `file`, `line` and `column` to a JSON object.
fn insert_place(object: &mut Map<String, Value>, place: &Place) {
    object.insert("file".into(), json!(place.file));
    object.insert("line".into(), json!(place.line));
    object.insert("column".into(), json!(place.column));
}

/// "1 more reflection", "985 more reflections".
fn more(count: usize, one: &str, many: &str) -> String {
    format!("{count} more {}", if count == 1 { one } else { many })
}

/// `[x, y, z]`.
fn triple(v: DVec3) -> Value {
    json!([v.x, v.y, v.z])
}

/// "(0.712, 0.5, 0)": a colour to three decimals.
fn colour(c: DVec3) -> String {
    format!("({}, {}, {})", short(c.x), short(c.y), short(c.z))
}

/// A number to three decimals, trailing zeros dropped.
fn short(value: f64) -> String {
    let text = format!("{value:.3}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0".to_string() } else { text.to_string() }
}
