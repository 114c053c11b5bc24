//! Showing renders in the terminal with viuer: the terminal's graphics
//! protocol where it has one (kitty, iTerm, sixel), coloured half-blocks
//! otherwise (which is also what works inside tmux).

use std::io::IsTerminal;

use image::{DynamicImage, RgbImage};

use crate::session::{PreviewSize, Size};

/// Rows kept free under a preview: one for the message after it, one for the prompt.
const ROWS_KEPT_FREE: u32 = 2;
/// The fewest rows a small preview takes, on a small terminal.
const SMALL_MIN_ROWS: u32 = 8;
/// Rows a lesson's pictures leave free at `small` for the lines shown with
/// them: the task (up to four lines), the verdict and its hint (three), and
/// the prompt.
const LESSON_TEXT_ROWS: u32 = 8;
/// Pixels rendered per terminal column when the terminal shows real images:
/// a cell is about 8 pixels wide and 16 high.
const PIXELS_PER_CELL_WITH_GRAPHICS: u32 = 8;

/// How the terminal can show images.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Method {
    /// Kitty, iTerm or sixel images.
    Graphics,
    /// `▀` characters with a foreground and a background colour: two pixels per cell.
    HalfBlocks,
}

/// Previews images in the terminal on standard output.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Preview {
    /// Inside tmux, which does not pass kitty or iTerm images through.
    in_tmux: bool,
    /// Whether half-blocks may use 24-bit colours.
    truecolor: bool,
    /// How much of the terminal a preview takes.
    pub(crate) size: PreviewSize,
}

impl Preview {
    /// A previewer, or `None` when previews are off: asked for with
    /// `--no-preview`, or standard output is not a terminal.
    pub(crate) fn new(no_preview: bool) -> Option<Preview> {
        let dumb = std::env::var("TERM").is_ok_and(|term| term == "dumb");
        if no_preview || dumb || !std::io::stdout().is_terminal() {
            return None;
        }
        let env = |name: &str| std::env::var(name).ok();
        Some(Preview { in_tmux: env("TMUX").is_some(), truecolor: has_truecolor(env), size: PreviewSize::Small })
    }

    /// How this terminal shows images. The first call asks the terminal, so it
    /// must not happen while the line editor is reading keys.
    pub(crate) fn method(&self) -> Method {
        let kitty = !self.in_tmux && viuer::get_kitty_support() != viuer::KittySupport::None;
        let iterm = !self.in_tmux && viuer::is_iterm_supported();
        if kitty || iterm || viuer::is_sixel_supported() { Method::Graphics } else { Method::HalfBlocks }
    }

    /// The cells (columns, rows) a preview may take: the terminal's, less
    /// the lines under it, or a part of them for a small preview.
    fn cells(&self) -> Size {
        self.cells_of(self.size)
    }

    fn cells_of(&self, size: PreviewSize) -> Size {
        let (columns, rows) = viuer::terminal_size();
        let all =
            Size { width: u32::from(columns).max(1), height: u32::from(rows).saturating_sub(ROWS_KEPT_FREE).max(1) };
        match size {
            PreviewSize::Small => Size {
                width: (all.width / 2).max(SMALL_MIN_ROWS * 2).min(all.width),
                height: (all.height / 3).max(SMALL_MIN_ROWS).min(all.height),
            },
            PreviewSize::Fit | PreviewSize::Off => all,
        }
    }

    /// The cells a lesson's goal and the learner's picture take together:
    /// at `small`, the terminal's width and its height less the lines of
    /// the task and the verdict, so that both pictures are large enough to
    /// show a highlight and a shadow and the task stays on screen (at 80x24,
    /// two pictures of 4:3 are each 35x28 pixels, against 18x15 in a small
    /// preview); at `fit`, the whole terminal.
    fn lesson_cells(&self) -> Size {
        let all = self.cells_of(PreviewSize::Fit);
        match self.size {
            PreviewSize::Small => Size {
                width: all.width,
                height: all.height.saturating_sub(LESSON_TEXT_ROWS).max(SMALL_MIN_ROWS).min(all.height),
            },
            PreviewSize::Fit | PreviewSize::Off => all,
        }
    }

    /// The image size worth rendering for a preview of an image shaped like
    /// `shape`: as large as the terminal shows it, never larger than `shape`.
    pub(crate) fn render_size(&self, shape: Size) -> Size {
        self.render_size_in(shape, self.cells())
    }

    /// [`Preview::render_size`] for a lesson's pair of pictures.
    pub(crate) fn lesson_render_size(&self, shape: Size) -> Size {
        self.render_size_in(shape, self.lesson_cells())
    }

    fn render_size_in(&self, shape: Size, cells: Size) -> Size {
        let scale = match self.method() {
            Method::Graphics => PIXELS_PER_CELL_WITH_GRAPHICS,
            Method::HalfBlocks => 1,
        };
        let fitted = fit_in_cells(shape, cells);
        let size = Size { width: fitted.width * scale, height: fitted.height * 2 * scale };
        let size = fit(shape, size);
        Size { width: size.width.min(shape.width).max(1), height: size.height.min(shape.height).max(1) }
    }

    /// Prints `image` scaled to fit its part of the terminal, never more
    /// than one cell per pixel across (a small render stays small); returns
    /// the rows it took.
    pub(crate) fn show(&self, image: &RgbImage) -> Result<u32, String> {
        self.show_in(image, self.cells())
    }

    /// [`Preview::show`] for a lesson's pair of pictures.
    pub(crate) fn show_lesson(&self, image: &RgbImage) -> Result<u32, String> {
        self.show_in(image, self.lesson_cells())
    }

    fn show_in(&self, image: &RgbImage, most: Size) -> Result<u32, String> {
        let shape = Size { width: image.width(), height: image.height() };
        let bounds = Size { width: most.width.min(shape.width), height: most.height.min(shape.height.div_ceil(2)) };
        let cells = fit_in_cells(shape, bounds);
        let config = viuer::Config {
            truecolor: self.truecolor,
            absolute_offset: false,
            width: Some(cells.width),
            height: Some(cells.height),
            use_kitty: !self.in_tmux,
            use_iterm: !self.in_tmux,
            ..viuer::Config::default()
        };
        viuer::print(&DynamicImage::ImageRgb8(image.clone()), &config).map(|(_, rows)| rows).map_err(|e| e.to_string())
    }
}

/// Whether the terminal shows 24-bit colours, from its environment
/// (`env` reads a variable). viuer (like most crates) trusts `COLORTERM`
/// only, which tmux, ssh and sudo often drop; the terminals that set other
/// variables are recognised too, and the rest get 256 colours.
fn has_truecolor(env: impl Fn(&str) -> Option<String>) -> bool {
    let says = |name: &str, words: &[&str]| env(name).is_some_and(|value| words.iter().any(|w| value.contains(w)));
    says("COLORTERM", &["truecolor", "24bit"])
        || env("TMUX").is_some()
        || says("TERM", &["direct", "truecolor", "kitty", "alacritty", "foot", "wezterm", "ghostty", "contour"])
        || says("TERM_PROGRAM", &["iTerm.app", "WezTerm", "vscode", "ghostty", "Hyper", "tmux"])
        || env("VTE_VERSION").and_then(|v| v.parse::<u32>().ok()).is_some_and(|version| version >= 3600)
        || env("KONSOLE_VERSION").is_some()
        || env("WT_SESSION").is_some()
}

/// The largest size with the proportions of `shape` that fits in `bounds`.
pub(crate) fn fit(shape: Size, bounds: Size) -> Size {
    let (w, h) = (u64::from(shape.width.max(1)), u64::from(shape.height.max(1)));
    let (bw, bh) = (u64::from(bounds.width.max(1)), u64::from(bounds.height.max(1)));
    // Width-limited when w/h >= bw/bh, that is w*bh >= bw*h.
    let (width, height) = if w * bh >= bw * h { (bw, (bw * h / w).max(1)) } else { ((bh * w / h).max(1), bh) };
    Size { width: width as u32, height: height as u32 }
}

/// The cells (columns, rows) an image shaped like `shape` takes when fitted
/// in `cells`, a cell being twice as high as it is wide.
pub(crate) fn fit_in_cells(shape: Size, cells: Size) -> Size {
    let pixels = fit(shape, Size { width: cells.width, height: cells.height * 2 });
    Size { width: pixels.width, height: pixels.height.div_ceil(2).max(1) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fit_keeps_proportions_and_bounds() {
        let bounds = Size { width: 80, height: 44 };
        assert_eq!(fit(Size { width: 640, height: 480 }, bounds), Size { width: 58, height: 44 });
        assert_eq!(fit(Size { width: 800, height: 200 }, bounds), Size { width: 80, height: 20 });
        assert_eq!(fit(Size { width: 1, height: 10000 }, bounds), Size { width: 1, height: 44 });
    }

    #[test]
    fn truecolor_is_recognised_without_colorterm() {
        let with = |pairs: &'static [(&'static str, &'static str)]| {
            has_truecolor(move |name| pairs.iter().find(|(n, _)| *n == name).map(|(_, v)| v.to_string()))
        };
        assert!(with(&[("COLORTERM", "truecolor")]));
        assert!(with(&[("TMUX", "/tmp/tmux-0/default,1,0"), ("TERM", "screen")]));
        assert!(with(&[("TERM", "xterm-kitty")]));
        assert!(with(&[("VTE_VERSION", "7402"), ("TERM", "xterm-256color")]));
        assert!(!with(&[("TERM", "xterm-256color")]));
        assert!(!with(&[("TERM", "linux")]));
    }

    #[test]
    fn cells_are_twice_as_high_as_wide() {
        let cells = fit_in_cells(Size { width: 640, height: 480 }, Size { width: 80, height: 22 });
        assert_eq!(cells, Size { width: 58, height: 22 });
        let cells = fit_in_cells(Size { width: 100, height: 100 }, Size { width: 200, height: 100 });
        assert_eq!(cells, Size { width: 200, height: 100 });
    }
}
