//! Line charts written as SVG and PNG (plotters), shared by the CLI's figures and reports.
//!
//! Text is rendered with the DejaVu Sans font committed under `crates/cli/assets/fonts/` (Bitstream Vera
//! licence, `crates/cli/assets/fonts/DejaVuSans-LICENSE.txt`) and compiled into the binary: plotters'
//! `ab_glyph` backend needs no system fontconfig or freetype, so a fresh machine can draw.
//! [`register_fonts`] registers it once; [`LineChart::write`] calls it.
//!
//! ```ignore
//! let chart = LineChart::new("Title", "x [m]", "y [N]")
//!     .series(Series::line("measured", points).color(0))
//!     .series(Series::line("model", other).color(0).dashed());
//! chart.write(Path::new("figures/name"))?; // figures/name.svg and figures/name.png
//! ```

// A shared module: the figures, the DEM triaxial test and the speed report each use a part.
#![allow(dead_code)]

use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use plotters::style::FontStyle;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The font every chart uses (DejaVu Sans 2.37, from Debian's `fonts-dejavu-core`).
static FONT: &[u8] = include_bytes!("../assets/fonts/DejaVuSans.ttf");

/// The family name charts ask plotters for.
const FAMILY: &str = "sans-serif";

/// Why a chart could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// The committed font could not be parsed.
    #[error("the built-in font could not be registered")]
    Font,
    /// A chart with no finite point to draw.
    #[error("chart `{0}` has no finite point to draw")]
    Empty(String),
    /// The drawing backend failed (e.g. the file could not be written).
    #[error("drawing {path}: {message}")]
    Draw {
        /// The file being written.
        path: PathBuf,
        /// The backend's message.
        message: String,
    },
}

/// Registers the built-in font with plotters (once per process; later calls return the first
/// result).
pub fn register_fonts() -> Result<(), PlotError> {
    static DONE: OnceLock<bool> = OnceLock::new();
    let ok = *DONE
        .get_or_init(|| plotters::style::register_font(FAMILY, FontStyle::Normal, FONT).is_ok());
    if ok { Ok(()) } else { Err(PlotError::Font) }
}

/// How a series' line is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LineStyle {
    /// A solid line.
    #[default]
    Solid,
    /// A dashed line.
    Dashed,
    /// No line (markers only; set [`Series::markers`]).
    None,
}

/// The palette series colours index into: black, then Okabe & Ito's (2008) colour-blind safe
/// colours (yellow darkened for a white background), then grey.
pub const PALETTE: [RGBColor; 9] = [
    RGBColor(0, 0, 0),
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(160, 140, 0),
    RGBColor(120, 120, 120),
];

/// One named series of `(x, y)` points (non-finite points are skipped).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend entry; an empty name keeps the series out of the legend.
    pub name: String,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line style.
    pub style: LineStyle,
    /// Index into [`PALETTE`] (wrapped).
    pub color: usize,
    /// Draw a marker at each point.
    pub markers: bool,
}

impl Series {
    /// A solid black line (colour 0).
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: LineStyle::Solid,
            color: 0,
            markers: false,
        }
    }

    /// This series with colour `index` of [`PALETTE`].
    pub fn color(mut self, index: usize) -> Self {
        self.color = index;
        self
    }

    /// This series dashed.
    pub fn dashed(mut self) -> Self {
        self.style = LineStyle::Dashed;
        self
    }

    /// This series with a marker at each point.
    pub fn markers(mut self) -> Self {
        self.markers = true;
        self
    }

    /// This series with the given line style.
    pub fn style(mut self, style: LineStyle) -> Self {
        self.style = style;
        self
    }

    fn rgb(&self) -> RGBColor {
        PALETTE[self.color % PALETTE.len()]
    }

    fn finite(&self) -> impl Iterator<Item = (f64, f64)> + Clone + '_ {
        self.points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
    }
}

/// Where the legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Inside the plot, lower right.
    #[default]
    LowerRight,
    /// Inside the plot, upper right.
    UpperRight,
    /// Inside the plot, upper left.
    UpperLeft,
    /// Inside the plot, lower left.
    LowerLeft,
    /// No legend.
    Hidden,
}

/// A line chart: several named series, axis labels, a legend.
#[derive(Debug, Clone, PartialEq)]
pub struct LineChart {
    /// Title above the plot (may be empty).
    pub title: String,
    /// Label of the x axis (with its unit).
    pub x_label: String,
    /// Label of the y axis (with its unit).
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
    /// Fixed x range; `None` fits the data.
    pub x_range: Option<(f64, f64)>,
    /// Fixed y range; `None` fits the data (with 5 % margins).
    pub y_range: Option<(f64, f64)>,
    /// Legend position.
    pub legend: Legend,
    /// Image size in pixels (PNG) or user units (SVG).
    pub size: (u32, u32),
}

impl LineChart {
    /// An empty chart, 900 x 600.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        LineChart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            x_range: None,
            y_range: None,
            legend: Legend::default(),
            size: (900, 600),
        }
    }

    /// This chart with one more series.
    pub fn series(mut self, s: Series) -> Self {
        self.series.push(s);
        self
    }

    /// This chart with a fixed x range.
    pub fn x_range(mut self, lo: f64, hi: f64) -> Self {
        self.x_range = Some((lo, hi));
        self
    }

    /// This chart with a fixed y range.
    pub fn y_range(mut self, lo: f64, hi: f64) -> Self {
        self.y_range = Some((lo, hi));
        self
    }

    /// This chart with the legend at `legend`.
    pub fn legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// Writes `<stem>.svg` and `<stem>.png`; returns the two paths.
    pub fn write(&self, stem: &Path) -> Result<[PathBuf; 2], PlotError> {
        self.write_scaled(stem, Scale::Linear)
    }

    /// Writes the chart as SVG to `path`.
    pub fn write_svg(&self, path: &Path) -> Result<(), PlotError> {
        register_fonts()?;
        self.render(
            &SVGBackend::new(path, self.size).into_drawing_area(),
            path,
            Scale::Linear,
        )
    }

    /// Writes the chart as PNG to `path`.
    pub fn write_png(&self, path: &Path) -> Result<(), PlotError> {
        register_fonts()?;
        self.render(
            &BitMapBackend::new(path, self.size).into_drawing_area(),
            path,
            Scale::Linear,
        )
    }

    /// The one prologue of every chart: the font, then `<stem>.svg` and `<stem>.png` drawn by
    /// [`LineChart::render`] on the two backends.
    fn write_scaled(&self, stem: &Path, scale: Scale) -> Result<[PathBuf; 2], PlotError> {
        register_fonts()?;
        let svg = stem.with_extension("svg");
        let png = stem.with_extension("png");
        self.render(
            &SVGBackend::new(&svg, self.size).into_drawing_area(),
            &svg,
            scale,
        )?;
        self.render(
            &BitMapBackend::new(&png, self.size).into_drawing_area(),
            &png,
            scale,
        )?;
        Ok([svg, png])
    }

    /// Draws the chart on `root` (written to `path`, which errors name): white background, the
    /// axes of `scale` with their series and legend, then presents it.
    fn render<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        path: &Path,
        scale: Scale,
    ) -> Result<(), PlotError> {
        let err = |e: &dyn std::fmt::Display| PlotError::Draw {
            path: path.to_path_buf(),
            message: e.to_string(),
        };
        root.fill(&WHITE).map_err(|e| err(&e))?;
        match scale {
            Scale::Linear => self.draw(root, &err)?,
            Scale::LogLog => self.draw_log_log(root, &err)?,
        }
        root.present().map_err(|e| err(&e))
    }

    /// The data's bounds `(x0, x1, y0, y1)`, or the fixed ranges.
    fn bounds(&self) -> Result<(f64, f64, f64, f64), PlotError> {
        let pts = || self.series.iter().flat_map(|s| s.finite());
        let fold = |f: fn(&(f64, f64)) -> f64| {
            pts()
                .map(|p| f(&p))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(v), hi.max(v))
                })
        };
        let (x0, x1) = self.x_range.unwrap_or_else(|| fold(|p| p.0));
        let (y0, y1) = match self.y_range {
            Some(r) => r,
            None => {
                let (lo, hi) = fold(|p| p.1);
                let m = 0.05 * (hi - lo).max(1e-300);
                (lo - m, hi + m)
            }
        };
        if !(x0.is_finite() && x1.is_finite() && y0.is_finite() && y1.is_finite()) {
            return Err(PlotError::Empty(self.title.clone()));
        }
        // A degenerate range still draws (a flat series).
        let widen = |lo: f64, hi: f64| {
            if hi > lo {
                (lo, hi)
            } else {
                let m = lo.abs().max(1.0) * 0.5;
                (lo - m, hi + m)
            }
        };
        let (x0, x1) = widen(x0, x1);
        let (y0, y1) = widen(y0, y1);
        Ok((x0, x1, y0, y1))
    }

    /// Linear axes: the series as lines, dashes and/or markers.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        err: &dyn Fn(&dyn std::fmt::Display) -> PlotError,
    ) -> Result<(), PlotError> {
        let (x0, x1, y0, y1) = self.bounds()?;
        let mut chart = self
            .frame(root)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| err(&e))?;
        self.draw_mesh(&mut chart).map_err(|e| err(&e))?;
        for s in &self.series {
            let color = s.rgb();
            let style = color.stroke_width(2);
            if s.markers {
                chart
                    .draw_series(s.finite().map(|p| Circle::new(p, 4, color.filled())))
                    .map_err(|e| err(&e))?;
            }
            // The line (transparent for markers only) carries the legend entry.
            let clear: ShapeStyle = TRANSPARENT.into();
            let (seg, first_end, second_start) = match s.style {
                LineStyle::Solid => (style, 24, 0),
                LineStyle::Dashed => (style, 9, 15),
                LineStyle::None => (clear, 24, 0),
            };
            let anno = match s.style {
                LineStyle::Dashed => chart
                    .draw_series(DashedLineSeries::new(s.finite(), 8, 5, style))
                    .map_err(|e| err(&e))?,
                _ => chart
                    .draw_series(LineSeries::new(s.finite(), seg))
                    .map_err(|e| err(&e))?,
            };
            if s.name.is_empty() {
                continue;
            }
            // Legend glyph: two segments (one solid line, or a dash and a gap) and a marker;
            // the parts a style does not use are transparent.
            let marker = if s.markers { color.filled() } else { clear };
            anno.label(&s.name).legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (first_end, 0)], seg)
                    + PathElement::new(vec![(second_start, 0), (24, 0)], seg)
                    + Circle::new((12, 0), 4, marker)
            });
        }
        self.draw_legend(&mut chart).map_err(|e| err(&e))?;
        Ok(())
    }
}

impl LineChart {
    /// The chart's frame: title, margins and label areas (linear and log-log charts alike).
    fn frame<'a, 'b, DB: DrawingBackend>(
        &'b self,
        root: &'a DrawingArea<DB, Shift>,
    ) -> ChartBuilder<'a, 'b, DB> {
        let mut b = ChartBuilder::on(root);
        b.caption(&self.title, (FAMILY, 22))
            .margin(15)
            .margin_right(35)
            .x_label_area_size(50)
            .y_label_area_size(70);
        b
    }

    /// The grid, tick labels and axis titles.
    fn draw_mesh<'a, DB, X, Y>(
        &self,
        chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        DB: DrawingBackend + 'a,
        X: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        chart
            .configure_mesh()
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FAMILY, 15))
            .axis_desc_style((FAMILY, 17))
            .light_line_style(RGBColor(235, 235, 235))
            .draw()
    }

    /// Draws the legend of the named series, where `self.legend` puts it.
    fn draw_legend<'a, DB, CT>(
        &self,
        chart: &mut ChartContext<'a, DB, CT>,
    ) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
    where
        DB: DrawingBackend + 'a,
        CT: CoordTranslate,
    {
        let position = match self.legend {
            Legend::LowerRight => SeriesLabelPosition::LowerRight,
            Legend::UpperRight => SeriesLabelPosition::UpperRight,
            Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
            Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
            Legend::Hidden => return Ok(()),
        };
        if !self.series.iter().any(|s| !s.name.is_empty()) {
            return Ok(());
        }
        chart
            .configure_series_labels()
            .position(position)
            .label_font((FAMILY, 15))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .draw()
    }
}

/// A tick label: at most 4 decimals, without trailing zeros (`20`, `0.25`, `1e-5`).
fn tick(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-3 || v.abs() >= 1e6) {
        return format!("{v:.1e}");
    }
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

// ------------------------------------------------------------------------------------------------
// Log-log charts (`creep report`'s speed-against-error frontier), through the same prologue.
// ------------------------------------------------------------------------------------------------

impl LineChart {
    /// Writes `<stem>.svg` and `<stem>.png` with both axes logarithmic (decades); points with a
    /// non-positive coordinate are skipped. Fixed ranges, if set, must be positive. Returns the
    /// two paths.
    pub fn write_log_log(&self, stem: &Path) -> Result<[PathBuf; 2], PlotError> {
        self.write_scaled(stem, Scale::LogLog)
    }

    /// Positive data bounds rounded out to decades `(x0, x1, y0, y1)`, or the fixed ranges.
    fn log_bounds(&self) -> Result<(f64, f64, f64, f64), PlotError> {
        let pts: Vec<(f64, f64)> = self
            .series
            .iter()
            .flat_map(|s| s.finite())
            .filter(|(x, y)| *x > 0.0 && *y > 0.0)
            .collect();
        let decades = |v: &mut dyn Iterator<Item = f64>| {
            let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
            let (lo, hi) = (
                10f64.powf(lo.log10().floor()),
                10f64.powf(hi.log10().ceil()),
            );
            if hi > lo { (lo, hi) } else { (lo, 10.0 * hi) }
        };
        let (x0, x1) = self
            .x_range
            .unwrap_or_else(|| decades(&mut pts.iter().map(|p| p.0)));
        let (y0, y1) = self
            .y_range
            .unwrap_or_else(|| decades(&mut pts.iter().map(|p| p.1)));
        let ok = |lo: f64, hi: f64| lo > 0.0 && hi > lo && hi.is_finite();
        if pts.is_empty() || !ok(x0, x1) || !ok(y0, y1) {
            return Err(PlotError::Empty(self.title.clone()));
        }
        Ok((x0, x1, y0, y1))
    }

    /// Log-log axes: the series as lines (unless `LineStyle::None`) with markers.
    fn draw_log_log<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        err: &dyn Fn(&dyn std::fmt::Display) -> PlotError,
    ) -> Result<(), PlotError> {
        let (x0, x1, y0, y1) = self.log_bounds()?;
        let mut chart = self
            .frame(root)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(|e| err(&e))?;
        self.draw_mesh(&mut chart).map_err(|e| err(&e))?;
        for s in &self.series {
            let color = s.rgb();
            let pts = || s.finite().filter(|(x, y)| *x > 0.0 && *y > 0.0);
            if s.style != LineStyle::None {
                let line = color.stroke_width(2);
                match s.style {
                    LineStyle::Dashed => chart
                        .draw_series(DashedLineSeries::new(pts(), 8, 5, line))
                        .map_err(|e| err(&e))?,
                    _ => chart
                        .draw_series(LineSeries::new(pts(), line))
                        .map_err(|e| err(&e))?,
                };
            }
            let anno = chart
                .draw_series(pts().map(|p| Circle::new(p, 5, color.filled())))
                .map_err(|e| err(&e))?;
            if !s.name.is_empty() {
                anno.label(&s.name)
                    .legend(move |(x, y)| Circle::new((x + 12, y), 5, color.filled()));
            }
        }
        self.draw_legend(&mut chart).map_err(|e| err(&e))?;
        Ok(())
    }
}

/// The axes of a chart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scale {
    /// Linear in both axes.
    Linear,
    /// Logarithmic in both axes (decades).
    LogLog,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_are_short() {
        assert_eq!(tick(20.0), "20");
        assert_eq!(tick(0.25), "0.25");
        assert_eq!(tick(-0.0), "0");
        assert_eq!(tick(0.1 + 0.2), "0.3");
        assert_eq!(tick(2e-5), "2.0e-5");
    }

    #[test]
    fn writes_svg_and_png_with_text() {
        let dir = std::env::temp_dir().join(format!("creep-plot-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let chart = LineChart::new("t", "x [m]", "y [N]")
            .series(Series::line("solid", vec![(0.0, 0.0), (1.0, 1.0)]).color(1))
            .series(Series::line("dashed", vec![(0.0, 1.0), (1.0, 0.0)]).dashed())
            .series(
                Series::line("markers", vec![(0.5, 0.5)])
                    .markers()
                    .style(LineStyle::None),
            )
            .legend(Legend::UpperRight);
        let [svg, png] = chart.write(&dir.join("chart")).unwrap();
        let text = std::fs::read_to_string(&svg).unwrap();
        assert!(text.contains("<svg") && text.contains("dashed") && text.contains("x [m]"));
        let bytes = std::fs::read(&png).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        // Nothing finite to draw is an error, not a panic.
        let empty = LineChart::new("e", "x", "y").series(Series::line("n", vec![(f64::NAN, 1.0)]));
        assert!(matches!(
            empty.write_svg(&dir.join("e.svg")),
            Err(PlotError::Empty(_))
        ));
        std::fs::remove_dir_all(&dir).ok();
    }
}
