//! Export of an evaluated scene to a POV-Ray 3.7 scene file
//! (`--export-pov`): camera, lights and every primitive with its texture,
//! in POV-Ray's conventions. The translation is the one
//! `benches/pov/solar.pov` was written and checked by hand with.

use std::fmt::Write;

use glam::{DMat3, DVec3};

use crate::scene::{Material, Primitive, Scene, Shape};

/// What is exported besides the scene: how it was made and how to render it.
pub struct Export<'a> {
    /// The scene file's name, for the header.
    pub source: &'a str,
    /// The time the scene was evaluated at.
    pub time: f64,
    /// Reflections followed (SPEC 6).
    pub depth: u32,
    /// The picture's size, for the render command in the header.
    pub width: u32,
    /// The picture's height.
    pub height: u32,
}

/// What cannot be matched exactly, said at the top of every export.
const DIFFERENCES: &str = "\
// What POV-Ray cannot match exactly:
// - planes: rayrepl's plane is seen only from the side its normal points to
//   (a ray from the solid side passes through); POV-Ray's plane is seen from
//   both sides. Pictures agree while the camera and every reflection stay on
//   the visible side.
// - colours: rayrepl clamps the colour to [0, 1] at every level of
//   reflection, POV-Ray only at the end, so very bright mirrors differ.
// - highlights: POV-Ray's `specular` with `roughness 1/n` gives ks (N.H)^n,
//   as rayrepl does, and `metallic` colours it with the surface; POV-Ray
//   may scale it slightly differently for large n.
// - the screen: rayrepl's optional bottom-edge convention (--screen bottom)
//   is not exported; the camera is the centred one of SPEC 5.
// - the image: write it linear, as rayrepl does, with File_Gamma=1.0, and
//   without anti-aliasing (rayrepl's --samples has no exact counterpart).
";

/// Why a scene cannot be exported: POV-Ray reads only finite numbers, and
/// a file it cannot read is not written.
#[derive(Debug, Clone, PartialEq)]
pub enum PovError {
    /// The scene reaches so far from the origin (`extent`) that its
    /// parallel lights cannot be put beyond it at a finite distance.
    TooLarge {
        /// How far the scene reaches along an axis (may be infinite).
        extent: f64,
    },
    /// A number to write for `what` (`sphere 3`, `the camera`) is not finite.
    NotFinite {
        /// The part of the scene, in words.
        what: String,
        /// The number.
        value: f64,
    },
}

impl std::fmt::Display for PovError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PovError::TooLarge { extent } if extent.is_finite() => write!(
                f,
                "cannot export to POV-Ray: the scene reaches {extent:e} from the origin, too far to put its \
                 parallel lights beyond it at a distance POV-Ray can read (it reads finite numbers only); \
                 scale the scene down"
            ),
            PovError::TooLarge { .. } => f.write_str(
                "cannot export to POV-Ray: the scene reaches beyond the largest finite number, so its \
                 parallel lights cannot be put beyond it; scale the scene down",
            ),
            PovError::NotFinite { what, value } => write!(
                f,
                "cannot export to POV-Ray: {what} would be written with the number {value}, \
                 which POV-Ray cannot read (it reads finite numbers only)"
            ),
        }
    }
}

impl std::error::Error for PovError {}

/// A number that is not finite, met while writing it.
#[derive(Debug, Clone, Copy)]
struct NotFinite(f64);

impl NotFinite {
    /// The error, saying it is a number of `what`.
    fn of(self, what: impl Into<String>) -> PovError {
        PovError::NotFinite { what: what.into(), value: self.0 }
    }
}

/// The scene as a POV-Ray 3.7 file, or why it cannot be one: every number
/// in it is finite, as POV-Ray reads them.
pub fn to_pov(scene: &Scene, export: &Export<'_>) -> Result<String, PovError> {
    let mut text = String::new();
    let Export { source, time, depth, width, height } = *export;
    let source = one_line(source);
    let _ = writeln!(text, "// {source} at time = {time}, exported by rayrepl for POV-Ray 3.7.");
    let _ = writeln!(text, "// Render it as rayrepl would ({width}x{height}, linear values, no anti-aliasing):");
    let _ = writeln!(text, "//   povray +Iscene.pov +Oscene.png +W{width} +H{height} -A -D File_Gamma=1.0");
    text.push_str(
        "//\n// Axes: POV-Ray's z points into the screen, rayrepl's towards the viewer:\n\
         // every z is negated. Textures: kd Ia C + kd (N.L) I C + ks (N.H)^n I C +\n\
         // ks reflection is ambient kd*Ia, diffuse kd, specular ks, roughness 1/n,\n\
         // metallic, reflection ks. Lights are directions: parallel lights far away.\n//\n",
    );
    text.push_str(DIFFERENCES);
    let _ = write!(
        text,
        "\n#version 3.7;\n\nglobal_settings {{\n  assumed_gamma 1.0\n  max_trace_level {}\n  \
         adc_bailout 0\n  ambient_light rgb 1\n}}\n\n",
        depth + 1
    );
    let camera = scene.camera;
    let location = vector(DVec3::new(0.0, 0.0, camera.distance)).map_err(|e| e.of("the camera"))?;
    let angle = number(camera.angle.to_degrees()).map_err(|e| e.of("the camera"))?;
    let _ = write!(
        text,
        "camera {{\n  perspective\n  location {location}\n  look_at <0, 0, 0>\n  right x * image_width / image_height\n  \
         up y\n  angle {angle}\n}}\n\n",
    );
    let far = light_distance(scene)?;
    for (k, light) in scene.lights.iter().enumerate() {
        let what = || format!("light {}", k + 1);
        let position = vector(light.direction * far).map_err(|e| e.of(what()))?;
        let intensity = number(light.intensity).map_err(|e| e.of(what()))?;
        let _ = writeln!(text, "light_source {{ {position} color rgb {intensity} parallel point_at <0, 0, 0> }}");
    }
    text.push('\n');
    for (k, primitive) in scene.primitives.iter().chain(&scene.timed_primitives).enumerate() {
        let written = object(primitive, scene.ambient).map_err(|e| e.of(format!("primitive {}", k + 1)))?;
        let _ = writeln!(text, "{written}");
    }
    Ok(text)
}

/// `text` on one line, for a comment: a control character (a line break
/// in a file's name) is written as its escape, or the rest of the name
/// would be read as POV-Ray's code.
fn one_line(text: &str) -> String {
    text.chars().map(|c| if c.is_control() { c.escape_debug().to_string() } else { c.to_string() }).collect()
}

/// One primitive as a POV-Ray object.
fn object(primitive: &Primitive, ambient: f64) -> Result<String, NotFinite> {
    let texture = texture(&primitive.material, ambient)?;
    Ok(match primitive.shape {
        Shape::Sphere { center, radius } => {
            format!("sphere {{ {}, {} {texture} }}", vector(center)?, number(radius)?)
        }
        Shape::Plane { normal, shift } => format!("plane {{ {}, {} {texture} }}", vector(normal)?, number(shift)?),
        Shape::Box { center, half, axes } => {
            // A point q of the box in its own axes is at c + A q; in POV-Ray's
            // axes (S = diag(1, 1, -1)) at S c + (S A S) (S q), and S q spans
            // the same symmetric box. POV-Ray's matrix takes the images of
            // x, y and z as its first three rows and the translation last.
            let flip = DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
            let turned = flip * axes * flip;
            let rows = [turned.x_axis, turned.y_axis, turned.z_axis, flip * center];
            let matrix: Vec<String> =
                rows.iter().flat_map(|row| row.to_array().map(number)).collect::<Result<_, _>>()?;
            format!(
                "box {{ {}, {} matrix <{}> {texture} }}",
                vector_as_is(-half)?,
                vector_as_is(half)?,
                matrix.join(", ")
            )
        }
    })
}

/// rayrepl's texture as POV-Ray's pigment and finish.
fn texture(material: &Material, ambient: f64) -> Result<String, NotFinite> {
    let Material { color, kd, ks, phong } = *material;
    Ok(format!(
        "pigment {{ color rgb {} }} finish {{ ambient {} diffuse {} specular {} roughness {} metallic reflection {} }}",
        vector_as_is(color)?,
        number(kd * ambient)?,
        number(kd)?,
        number(ks)?,
        number(1.0 / phong)?,
        number(ks)?
    ))
}

/// How far away the parallel lights are put: well beyond everything in the
/// scene, whatever its scale (a parallel light in POV-Ray casts shadows
/// only from objects between it and the point lit). Everything lies in the
/// cube of half side `extent` about the origin, so within `sqrt(3) extent`
/// of it: 10^6 times `extent` where that is a finite number, twice it
/// otherwise, or refused when even that is not.
fn light_distance(scene: &Scene) -> Result<f64, PovError> {
    let extent = scene.primitives.iter().chain(&scene.timed_primitives).fold(scene.camera.distance.abs(), |far, p| {
        match p.shape {
            Shape::Sphere { center, radius } => far.max(center.abs().max_element() + radius),
            Shape::Plane { shift, .. } => far.max(shift.abs()),
            Shape::Box { center, half, .. } => far.max(center.abs().max_element() + half.length()),
        }
    });
    let extent = extent.max(f64::MIN_POSITIVE);
    [1e6, 2.0].map(|times| times * extent).into_iter().find(|far| far.is_finite()).ok_or(PovError::TooLarge { extent })
}

/// A point or direction of rayrepl's axes in POV-Ray's: z negated.
fn vector(v: DVec3) -> Result<String, NotFinite> {
    vector_as_is(DVec3::new(v.x, v.y, -v.z))
}

/// Three numbers as a POV-Ray vector.
fn vector_as_is(v: DVec3) -> Result<String, NotFinite> {
    Ok(format!("<{}, {}, {}>", number(v.x)?, number(v.y)?, number(v.z)?))
}

/// A number as POV-Ray reads it: the shortest text that reads back the same
/// f64, with an exponent for the very large and the very small; none for
/// infinities and NaN, which POV-Ray has no words for.
fn number(x: f64) -> Result<String, NotFinite> {
    if !x.is_finite() {
        return Err(NotFinite(x));
    }
    let x = if x == 0.0 { 0.0 } else { x };
    Ok(format!("{x:?}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Camera, Light, TimeUse};

    fn material() -> Material {
        Material { color: DVec3::new(1.0, 0.5, 0.0), kd: 0.8, ks: 0.25, phong: 20.0 }
    }

    fn export() -> Export<'static> {
        Export { source: "test.ray", time: 2.0, depth: 5, width: 80, height: 60 }
    }

    fn scene(shape: Shape) -> Scene {
        Scene {
            camera: Camera { distance: 10.0, angle: std::f64::consts::FRAC_PI_2 },
            ambient: 0.5,
            lights: vec![Light { direction: DVec3::new(0.0, 0.6, 0.8), intensity: 0.7 }],
            primitives: vec![Primitive { shape, material: material() }],
            timed_primitives: Vec::new(),
            time_use: TimeUse::default(),
        }
    }

    #[test]
    fn z_is_negated_and_textures_become_finishes() {
        let text = to_pov(&scene(Shape::Sphere { center: DVec3::new(1.0, 2.0, 3.0), radius: 0.5 }), &export())
            .expect("finite");
        assert!(text.contains("location <0.0, 0.0, -10.0>"), "{text}");
        assert!(text.contains("angle 90.0"), "{text}");
        assert!(text.contains("max_trace_level 6"), "{text}");
        assert!(text.contains("sphere { <1.0, 2.0, -3.0>, 0.5 pigment { color rgb <1.0, 0.5, 0.0> }"), "{text}");
        // ambient kd * Ia = 0.8 * 0.5; roughness 1 / 20.
        assert!(
            text.contains("finish { ambient 0.4 diffuse 0.8 specular 0.25 roughness 0.05 metallic reflection 0.25 }"),
            "{text}"
        );
        // The light 10^6 times the camera distance away, towards (0, 0.6, -0.8) in POV-Ray's axes.
        assert!(text.contains("light_source { <0.0, 6000000.0, -8000000.0> color rgb 0.7 parallel"), "{text}");
        assert!(text.contains("+W80 +H60") && text.contains("seen only from the side its normal points to"));
    }

    #[test]
    fn a_turned_box_keeps_its_handedness() {
        // A quarter turn about y: rayrepl's x axis goes to -z.
        let axes = DMat3::from_rotation_y(std::f64::consts::FRAC_PI_2);
        let shape = Shape::Box { center: DVec3::new(0.0, 0.0, 2.0), half: DVec3::new(1.0, 2.0, 3.0), axes };
        let text = to_pov(&scene(shape), &export()).expect("finite");
        let line = text.lines().find(|line| line.starts_with("box")).expect("a box");
        assert!(line.starts_with("box { <-1.0, -2.0, -3.0>, <1.0, 2.0, 3.0> matrix <"), "{line}");
        // In POV-Ray's axes the box's x goes to +z (rayrepl's -z, negated), and its centre to z = -2.
        let flip = DMat3::from_diagonal(DVec3::new(1.0, 1.0, -1.0));
        let turned = flip * axes * flip;
        assert!((turned.x_axis - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-12);
        assert!((turned.determinant() - 1.0).abs() < 1e-12);
        assert!(line.contains(", 0.0, 0.0, -2.0> pigment"), "{line}");
    }

    #[test]
    fn numbers_read_back_exactly_at_any_scale() {
        let number = |x| number(x).expect("finite");
        assert_eq!(number(1e-200), "1e-200");
        assert_eq!(number(-0.0), "0.0");
        assert_eq!(number(2.5), "2.5");
        assert_eq!(number(1e150).parse::<f64>(), Ok(1e150));
    }

    #[test]
    fn a_file_name_with_a_line_break_stays_in_the_comment() {
        let export = Export { source: "a\n#declare x = 1;\r.ray", ..export() };
        let text = to_pov(&scene(Shape::Sphere { center: DVec3::ZERO, radius: 1.0 }), &export).expect("finite");
        assert!(text.starts_with("// a\\n#declare x = 1;\\r.ray at time = 2,"), "{text}");
        assert!(!text.lines().any(|line| line.starts_with("#declare")), "{text}");
    }

    #[test]
    fn every_number_of_a_huge_scene_is_finite_or_the_export_is_refused() {
        let huge = to_pov(&scene(Shape::Sphere { center: DVec3::ZERO, radius: 1e303 }), &export()).expect("finite");
        let light = huge.lines().find(|line| line.starts_with("light_source")).expect("a light");
        assert!(light.starts_with("light_source { <0.0, 1.2e303, -1.6e303> color rgb 0.7"), "{light}");
        assert!(!huge.contains("inf") && !huge.contains("NaN"), "{huge}");
        let too_far = scene(Shape::Sphere { center: DVec3::new(1.7e308, 0.0, 0.0), radius: 1e308 });
        assert!(matches!(to_pov(&too_far, &export()), Err(PovError::TooLarge { .. })));
        let message = to_pov(&scene(Shape::Sphere { center: DVec3::ZERO, radius: 1e308 }), &export())
            .expect_err("2e308 is not finite")
            .to_string();
        assert!(message.starts_with("cannot export to POV-Ray: the scene reaches 1e308 from the origin"), "{message}");
        let mut flat = scene(Shape::Sphere { center: DVec3::ZERO, radius: 1.0 });
        flat.primitives[0].material.phong = 0.0;
        let error = to_pov(&flat, &export()).expect_err("roughness 1/0");
        assert_eq!(error, PovError::NotFinite { what: "primitive 1".into(), value: f64::INFINITY });
    }
}
