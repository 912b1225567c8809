//! How large figures are drawn: for the screen (the default), or for print at the width of a
//! paper's column (3.5 in) or page (7 in), where one user unit of the SVG is one point and
//! every text is at least 8 pt. `--print-width` (compare, sweep) chooses; the SVG's root then
//! carries its size in inches, so a paper includes it at 100% and its text prints as sized.
use clap::ValueEnum;

/// The width figures are made for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, ValueEnum)]
pub enum PrintWidth {
    /// A browser or a slide: about 760 pixels wide, 13-21 px text.
    #[default]
    Screen,
    /// One column of a two-column paper: 3.5 inches, text 8-9 pt.
    #[value(name = "3.5in")]
    Column,
    /// A full page width (both columns): 7 inches, text 8-10 pt.
    #[value(name = "7in")]
    Page,
}

/// The sizes a figure is drawn with, in SVG user units (points when printed).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// The figure's width.
    pub width: f64,
    /// Its width in inches when printed (`None`: for the screen, in pixels).
    pub inches: Option<f64>,
    /// Titles.
    pub title: f64,
    /// Axis descriptions, column and row labels.
    pub label: f64,
    /// Tick labels, legends, point labels: the smallest text.
    pub small: f64,
    /// Space around and between parts.
    pub gap: f64,
    /// Line width of curves.
    pub stroke: f64,
}

/// The smallest text a printed figure has, in points.
pub const MIN_PRINT_POINTS: f64 = 8.0;

/// plotters' SVG backend takes whole font sizes s and writes them as `font-size` s / 1.24; the
/// sizes given to plotters are scaled by this and rounded up, so that the written size is at
/// least the style's.
const PLOTTERS_FONT_SCALE: f64 = 1.24;

impl PrintWidth {
    pub fn style(self) -> Style {
        let print = |inches: f64, title: f64| Style {
            width: inches * 72.0,
            inches: Some(inches),
            title,
            label: MIN_PRINT_POINTS + 0.5,
            small: MIN_PRINT_POINTS,
            gap: 3.0,
            stroke: 1.0,
        };
        match self {
            Self::Screen => Style {
                width: 760.0,
                inches: None,
                title: 21.0,
                label: 17.0,
                small: 15.0,
                gap: 8.0,
                stroke: 2.0,
            },
            Self::Column => print(3.5, 9.0),
            Self::Page => print(7.0, 10.0),
        }
    }
}

impl Style {
    /// The size to give plotters for text written at `size` or a little more.
    pub fn plotters(size: f64) -> f64 {
        (size * PLOTTERS_FONT_SCALE).ceil()
    }

    /// The attributes of the root `<svg>` of a `width` × `height` figure: its size (in inches
    /// for print) and its view box in user units.
    pub fn root_size(&self, width: f64, height: f64) -> String {
        match self.inches {
            Some(inches) => format!(
                r#"width="{inches}in" height="{:.3}in" viewBox="0 0 {width} {height}""#,
                inches * height / width
            ),
            None => format!(r#"width="{width}" height="{height}" viewBox="0 0 {width} {height}""#),
        }
    }

    /// `svg` (a document plotters drew at the figure's size in user units) with the root's
    /// size attributes of [`Style::root_size`].
    pub fn sized(&self, svg: &str, (width, height): (u32, u32)) -> String {
        let plotted =
            format!(r#"width="{width}" height="{height}" viewBox="0 0 {width} {height}""#);
        svg.replacen(
            &plotted,
            &self.root_size(f64::from(width), f64::from(height)),
            1,
        )
    }

    /// `text` broken into lines of at most about `width` user units at `size` (a character
    /// of a sans-serif font is taken as 0.55 em wide); words are not split.
    pub fn wrap(text: &str, width: f64, size: f64) -> Vec<String> {
        let most = ((width / (0.55 * size)).floor() as usize).max(1);
        let mut lines: Vec<String> = Vec::new();
        for word in text.split(' ') {
            match lines.last_mut() {
                Some(line) if line.chars().count() + 1 + word.chars().count() <= most => {
                    line.push(' ');
                    line.push_str(word);
                }
                _ => lines.push(word.to_string()),
            }
        }
        lines
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn print_sizes_are_points_and_inches() {
        let s = PrintWidth::Column.style();
        assert_eq!((s.width, s.inches), (252.0, Some(3.5)));
        assert!(s.small >= MIN_PRINT_POINTS && s.label >= s.small && s.title >= s.label);
        assert_eq!(
            s.root_size(252.0, 126.0),
            r#"width="3.5in" height="1.750in" viewBox="0 0 252 126""#
        );
        assert_eq!(PrintWidth::Page.style().width, 504.0);
        let screen = PrintWidth::Screen.style();
        assert_eq!(
            screen.sized(
                r#"<svg width="760" height="500" viewBox="0 0 760 500">"#,
                (760, 500)
            ),
            r#"<svg width="760" height="500" viewBox="0 0 760 500">"#
        );
    }

    #[test]
    fn text_wraps_at_words_to_the_width() {
        let lines = Style::wrap("ellipsoid 12.3 lights/px, FDR 0.12", 50.0, 8.0);
        assert_eq!(lines, ["ellipsoid", "12.3", "lights/px,", "FDR 0.12"]);
        assert_eq!(Style::wrap("one", 1.0, 8.0), ["one"]);
    }
}
