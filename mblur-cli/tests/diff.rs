//! `mblur diff`: metrics of two image files against values computed by hand.

mod common;

use common::mblur;
use mblur::Image;

fn save(dir: &std::path::Path, name: &str, image: &Image) -> std::path::PathBuf {
    let path = dir.join(name);
    mblur_scene::image_io::save(image, &path).unwrap();
    path
}

/// A 16 x 16 image: a horizontal ramp in every channel.
fn ramp() -> Image {
    let (w, h) = (16u32, 16u32);
    Image {
        width: w,
        height: h,
        pixels: (0..w * h).map(|i| [(i % w) as f32 / 16.0; 3]).collect(),
    }
}

fn run(args: &[&std::path::Path], metric: Option<&str>) -> String {
    let mut cmd = mblur();
    cmd.arg("diff").args(args);
    if let Some(m) = metric {
        cmd.args(["--metric", m]);
    }
    let out = cmd.assert().success();
    String::from_utf8_lossy(&out.get_output().stdout)
        .trim()
        .to_string()
}

#[test]
fn an_image_against_itself_has_zero_error_and_infinite_psnr() {
    let dir = tempfile::tempdir().unwrap();
    let a = save(dir.path(), "a.pfm", &ramp());
    let b = save(dir.path(), "b.exr", &ramp());
    assert_eq!(run(&[&a, &b], Some("rmse")), "0");
    assert_eq!(run(&[&a, &b], Some("psnr")), "inf");
    assert_eq!(run(&[&a, &b], Some("ssim")).parse::<f64>().unwrap(), 1.0);
    assert!(run(&[&a, &b], None).contains("PSNR inf dB"));
}

#[test]
fn a_shifted_copy_gives_the_hand_computed_error() {
    // Shifted one column right (the first column repeated): every pixel but those of the
    // first column differs by 1/16 in each channel, so MSE = (15/16) (1/16)^2.
    let dir = tempfile::tempdir().unwrap();
    let base = ramp();
    let mut shifted = base.clone();
    for y in 0..16usize {
        for x in (1..16usize).rev() {
            shifted.pixels[y * 16 + x] = base.pixels[y * 16 + x - 1];
        }
    }
    let a = save(dir.path(), "a.pfm", &shifted);
    let b = save(dir.path(), "b.pfm", &base);
    let mse = 15.0 / 16.0 / 256.0;
    let rmse: f64 = run(&[&a, &b], Some("rmse")).parse().unwrap();
    assert!((rmse - f64::sqrt(mse)).abs() < 1e-7, "{rmse}");
    let psnr: f64 = run(&[&a, &b], Some("psnr")).parse().unwrap();
    assert!((psnr - 10.0 * (1.0 / mse).log10()).abs() < 1e-5, "{psnr}");
    let max: f64 = run(&[&a, &b], Some("max-abs")).parse().unwrap();
    assert!((max - 1.0 / 16.0).abs() < 1e-7, "{max}");
}

#[test]
fn a_png_reads_back_as_linear_within_its_8_bit_rounding() {
    let dir = tempfile::tempdir().unwrap();
    let a = save(dir.path(), "a.png", &ramp());
    let b = save(dir.path(), "b.pfm", &ramp());
    let max: f64 = run(&[&a, &b], Some("max-abs")).parse().unwrap();
    // Rounding to 8-bit sRGB moves a value by at most half a step, 0.5 / 255 in sRGB, and
    // d(linear)/d(sRGB) is at most 2.4 / 1.055 on [0, 1] (its value at 1).
    let bound = 0.5 / 255.0 * 2.4 / 1.055;
    assert!(max <= bound, "{max} > {bound}");
}

#[test]
fn images_of_different_sizes_are_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let a = save(dir.path(), "a.pfm", &ramp());
    let b = save(dir.path(), "b.pfm", &Image::filled(8, 8, [0.0; 3]));
    let out = mblur()
        .arg("diff")
        .args([&a, &b])
        .assert()
        .failure()
        .code(1);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(stderr.contains("16 x 16 against 8 x 8"), "{stderr}");
}
