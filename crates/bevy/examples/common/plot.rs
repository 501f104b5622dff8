//! The live plot: lines and points rasterised into a texture shown by a UI image.

use bevy::asset::RenderAssetUsages;
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};

/// A plot drawn on the CPU into an RGBA image each frame (simple and renderer-agnostic).
#[derive(Debug, Clone)]
pub struct Plot {
    /// Width and height [px].
    pub size: UVec2,
    /// x range (data units).
    pub x: (f64, f64),
    /// y range (data units).
    pub y: (f64, f64),
    pixels: Vec<u8>,
}

/// Plot colours.
pub mod colours {
    /// Background.
    pub const BG: [u8; 4] = [16, 18, 22, 220];
    /// Axes and grid.
    pub const AXIS: [u8; 4] = [110, 110, 120, 255];
    /// Grid.
    pub const GRID: [u8; 4] = [45, 48, 55, 255];
    /// Theory lines.
    pub const THEORY: [u8; 4] = [235, 235, 235, 255];
    /// Coulomb.
    pub const COULOMB: [u8; 4] = [90, 150, 255, 255];
    /// Creep.
    pub const CREEP: [u8; 4] = [255, 200, 40, 255];
    /// Rolling torque.
    pub const TORQUE: [u8; 4] = [240, 90, 90, 255];
    /// Something else.
    pub const OTHER: [u8; 4] = [110, 220, 120, 255];
}

impl Plot {
    /// An empty plot.
    pub fn new(size: UVec2, x: (f64, f64), y: (f64, f64)) -> Self {
        let mut p = Self {
            size,
            x,
            y,
            pixels: vec![0; (size.x * size.y * 4) as usize],
        };
        p.clear();
        p
    }
    /// Clears to the background and draws the axes (through 0 where in range) and a grid of
    /// `grid` divisions.
    pub fn clear(&mut self) {
        for px in self.pixels.chunks_exact_mut(4) {
            px.copy_from_slice(&colours::BG);
        }
        let n = 5;
        for i in 0..=n {
            let f = i as f64 / n as f64;
            let gx = self.x.0 + f * (self.x.1 - self.x.0);
            let gy = self.y.0 + f * (self.y.1 - self.y.0);
            self.line((gx, self.y.0), (gx, self.y.1), colours::GRID);
            self.line((self.x.0, gy), (self.x.1, gy), colours::GRID);
        }
        let x0 = 0f64.clamp(self.x.0, self.x.1);
        let y0 = 0f64.clamp(self.y.0, self.y.1);
        self.line((x0, self.y.0), (x0, self.y.1), colours::AXIS);
        self.line((self.x.0, y0), (self.x.1, y0), colours::AXIS);
    }
    fn to_px(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let w = f64::from(self.size.x - 1);
        let h = f64::from(self.size.y - 1);
        (
            (x - self.x.0) / (self.x.1 - self.x.0) * w,
            h - (y - self.y.0) / (self.y.1 - self.y.0) * h,
        )
    }
    fn put(&mut self, x: i64, y: i64, c: [u8; 4]) {
        if x >= 0 && y >= 0 && (x as u32) < self.size.x && (y as u32) < self.size.y {
            let i = ((y as u32 * self.size.x + x as u32) * 4) as usize;
            self.pixels[i..i + 4].copy_from_slice(&c);
        }
    }
    /// A line between two data points (clipped to the image).
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), c: [u8; 4]) {
        let (pa, pb) = (self.to_px(a), self.to_px(b));
        if !(pa.0.is_finite() && pa.1.is_finite() && pb.0.is_finite() && pb.1.is_finite()) {
            return;
        }
        let lim = 4.0 * f64::from(self.size.x.max(self.size.y));
        let clamp = |v: f64| v.clamp(-lim, lim);
        let (x0, y0, x1, y1) = (clamp(pa.0), clamp(pa.1), clamp(pb.0), clamp(pb.1));
        let n = (x1 - x0).abs().max((y1 - y0).abs()).ceil().max(1.0) as i64;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let x = x0 + t * (x1 - x0);
            let y = y0 + t * (y1 - y0);
            self.put(x.round() as i64, y.round() as i64, c);
        }
    }
    /// A polyline through data points.
    pub fn polyline(&mut self, pts: &[(f64, f64)], c: [u8; 4]) {
        for w in pts.windows(2) {
            self.line(w[0], w[1], c);
        }
    }
    /// A filled square marker of half-width `r` pixels at a data point.
    pub fn point(&mut self, p: (f64, f64), r: i64, c: [u8; 4]) {
        let (x, y) = self.to_px(p);
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        let (x, y) = (x.round() as i64, y.round() as i64);
        for dy in -r..=r {
            for dx in -r..=r {
                self.put(x + dx, y + dy, c);
            }
        }
    }
    /// A new image of the plot's size.
    pub fn image(&self) -> Image {
        Image::new(
            Extent3d {
                width: self.size.x,
                height: self.size.y,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            self.pixels.clone(),
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::default(),
        )
    }
    /// Copies the pixels into `image` (made by [`Plot::image`]).
    pub fn write(&self, image: &mut Image) {
        image.data = Some(self.pixels.clone());
    }
}

/// Spawns a plot image at the window's right edge, `bottom` pixels above the bottom, with a
/// caption above it (a UI text node, returned for updates); returns the image handle and the
/// caption entity.
pub fn spawn_plot(
    commands: &mut Commands,
    images: &mut Assets<Image>,
    plot: &Plot,
    caption: &str,
    bottom: f32,
) -> (Handle<Image>, Entity) {
    let handle = images.add(plot.image());
    let mut caption_entity = Entity::PLACEHOLDER;
    commands
        .spawn(Node {
            position_type: PositionType::Absolute,
            right: Val::Px(6.0),
            bottom: Val::Px(bottom),
            flex_direction: FlexDirection::Column,
            align_items: AlignItems::End,
            ..default()
        })
        .with_children(|p| {
            caption_entity = p
                .spawn((
                    Node {
                        padding: UiRect::all(Val::Px(4.0)),
                        ..default()
                    },
                    BackgroundColor(Color::srgba(0.0, 0.0, 0.0, 0.6)),
                    Text::new(caption),
                    TextFont::from_font_size(12.0),
                    TextColor(Color::srgb(0.9, 0.9, 0.9)),
                ))
                .id();
            p.spawn((
                Node {
                    width: Val::Px(plot.size.x as f32),
                    height: Val::Px(plot.size.y as f32),
                    ..default()
                },
                ImageNode::new(handle.clone()),
            ));
        });
    (handle, caption_entity)
}

/// `x` rounded to a "nice" value at or above it (1, 2 or 5 times a power of ten), for axes.
pub fn nice_ceil(x: f64) -> f64 {
    if !(x > 0.0) || !x.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= x {
            return m * p;
        }
    }
    10.0 * p
}
