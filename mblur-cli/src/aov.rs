//! The AOV flags of `mblur render`: `--aov` picks the layers written next to the image into a
//! multi-channel EXR, `--sharp-at` the instant of the sharp, id and motion layers.

use std::path::Path;

use mblur::{AovOptions, AovSet};
use mblur_scene::Error;

/// One AOV layer, as `--aov` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum Layer {
    /// Shutter-averaged view depth of the nearest surface (`depth.Z`).
    Depth,
    /// Open-to-close screen displacement of the surface visible at --sharp-at, in pixels
    /// (`motion.X`, `motion.Y`).
    Motion,
    /// The image at --sharp-at (`sharp.R`, `sharp.G`, `sharp.B`).
    Sharp,
    /// 1 + object index of the surface visible at --sharp-at, 0 for none (`id.X`).
    Id,
    /// Fraction of the shutter the pixel centre is covered by a surface (`coverage.X`).
    Coverage,
}

#[derive(clap::Args)]
pub(crate) struct AovArgs {
    /// AOV layers written with the image into a multi-channel EXR (-o must end in .exr):
    /// a comma-separated list of depth, motion, sharp, id, coverage.
    #[arg(long, value_enum, value_delimiter = ',')]
    aov: Vec<Layer>,
    /// The instant, in [0, 1] of the shutter, of the sharp, id and motion layers
    /// (default 0.5).
    #[arg(long)]
    sharp_at: Option<f64>,
}

impl AovArgs {
    /// The layers and options asked for (`None` without --aov), checked against the output.
    pub(crate) fn request(&self, output: &Path) -> Result<Option<(AovSet, AovOptions)>, Error> {
        if self.aov.is_empty() {
            if self.sharp_at.is_some() {
                return Err(Error::Option {
                    option: "--sharp-at".into(),
                    message: "sets the instant of the AOV layers and needs --aov".into(),
                });
            }
            return Ok(None);
        }
        let exr = mblur_scene::image_io::Format::from_path(output).ok();
        if exr != Some(mblur_scene::image_io::Format::Exr) {
            return Err(Error::Option {
                option: "--aov".into(),
                message: format!(
                    "layers are written into a multi-channel EXR, but the output is {} \
                     (use -o NAME.exr)",
                    output.display()
                ),
            });
        }
        let mut set = AovSet::default();
        for layer in &self.aov {
            match layer {
                Layer::Depth => set.depth = true,
                Layer::Motion => set.motion = true,
                Layer::Sharp => set.sharp = true,
                Layer::Id => set.id = true,
                Layer::Coverage => set.coverage = true,
            }
        }
        let options = AovOptions {
            sharp_at: self.sharp_at.unwrap_or(0.5),
            ..AovOptions::default()
        };
        options.validate().map_err(crate::options::flag_error)?;
        Ok(Some((set, options)))
    }
}
