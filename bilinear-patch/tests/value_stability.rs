//! Value-stability tests: exact bit patterns of deterministic outputs, so that any change
//! in the arithmetic (operation order, a new refinement step) is noticed and reviewed. The
//! values themselves are checked for correctness in `hard_cases.rs` and `properties.rs`.

use bilinear_patch::{FastPatch, Patch, Prism, Ray};

fn bits64(h: &[bilinear_patch::Hit<f64>]) -> Vec<[u64; 3]> {
    h.iter()
        .map(|x| [x.t.to_bits(), x.u.to_bits(), x.v.to_bits()])
        .collect()
}

#[test]
fn pinned_patch_hits() {
    let c = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.1, 0.4],
        [0.9, 1.2, -0.3],
        [-0.1, 0.8, 0.2],
    ];
    let h = Patch::new(c).intersect([0.3, 0.4, 2.0], [0.1, 0.05, -1.0], 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![[0x3ffea5cced7eeee8, 0x3fe13374fd930944, 0x3fdd6df01980fdae]]
    );
    let cf = c.map(|p| p.map(|x| x as f32));
    let h = Patch::new(cf).intersect([0.3f32, 0.4, 2.0], [0.1, 0.05, -1.0], 0.0, f32::INFINITY);
    let b: Vec<[u32; 3]> = h
        .iter()
        .map(|x| [x.t.to_bits(), x.u.to_bits(), x.v.to_bits()])
        .collect();
    assert_eq!(b, vec![[0x3ff52e67, 0x3f099ba8, 0x3eeb6f82]]);
    let s = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    let h = Patch::new(s).intersect([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![
            [0x3fd22953041e1d58, 0x3fc785d93b6f6de2, 0x3fc785d93b6f6de3],
            [0x3fed51bce45757bb, 0x3fea1e89b1242488, 0x3fea1e89b1242488]
        ]
    );
}

/// The non-watertight `FastPatch::intersect_world` on the inputs of `pinned_patch_hits`: within one ulp of
/// the watertight test's values there (u in f64 and v in f32 differ in the last bit).
#[test]
fn pinned_fast_patch_hits() {
    let c = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.1, 0.4],
        [0.9, 1.2, -0.3],
        [-0.1, 0.8, 0.2],
    ];
    let h =
        FastPatch::new(c).intersect_world([0.3, 0.4, 2.0], [0.1, 0.05, -1.0], 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![[0x3ffea5cced7eeee8, 0x3fe13374fd930945, 0x3fdd6df01980fdae]]
    );
    let cf = c.map(|p| p.map(|x| x as f32));
    let h = FastPatch::new(cf).intersect_world(
        [0.3f32, 0.4, 2.0],
        [0.1, 0.05, -1.0],
        0.0,
        f32::INFINITY,
    );
    let b: Vec<[u32; 3]> = h
        .iter()
        .map(|x| [x.t.to_bits(), x.u.to_bits(), x.v.to_bits()])
        .collect();
    assert_eq!(b, vec![[0x3ff52e67, 0x3f099ba8, 0x3eeb6f81]]);
    let s = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    let h =
        FastPatch::new(s).intersect_world([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0], 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![
            [0x3fd22953041e1d58, 0x3fc785d93b6f6de2, 0x3fc785d93b6f6de2],
            [0x3fed51bce45757bb, 0x3fea1e89b1242488, 0x3fea1e89b1242488]
        ]
    );
}

/// The ray-space `FastPatch::intersect_ray` on the same inputs, pinned: in f64 the same bits
/// as the watertight test (`pinned_patch_hits`), in f32 t and u one ulp above them (v comes
/// from its own quadratic, so the saddle's first v has the watertight test's bits too).
#[test]
fn pinned_fast_patch_ray_space_hits() {
    let c = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.1, 0.4],
        [0.9, 1.2, -0.3],
        [-0.1, 0.8, 0.2],
    ];
    let ray = Ray::new([0.3, 0.4, 2.0], [0.1, 0.05, -1.0]).expect("finite ray");
    let h = FastPatch::new(c).intersect_ray(&ray, 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![[0x3ffea5cced7eeee8, 0x3fe13374fd930944, 0x3fdd6df01980fdae]]
    );
    let cf = c.map(|p| p.map(|x| x as f32));
    let ray = Ray::new([0.3f32, 0.4, 2.0], [0.1, 0.05, -1.0]).expect("finite ray");
    let h = FastPatch::new(cf).intersect_ray(&ray, 0.0, f32::INFINITY);
    let b: Vec<[u32; 3]> = h
        .iter()
        .map(|x| [x.t.to_bits(), x.u.to_bits(), x.v.to_bits()])
        .collect();
    assert_eq!(b, vec![[0x3ff52e68, 0x3f099ba9, 0x3eeb6f81]]);
    let s = [
        [0.0f64, 0.0, 0.0],
        [1.0, 0.0, 1.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 1.0],
    ];
    let ray = Ray::new([-0.1, -0.1, 0.3], [1.0, 1.0, 0.0]).expect("finite ray");
    let h = FastPatch::new(s).intersect_ray(&ray, 0.0, f64::INFINITY);
    assert_eq!(
        bits64(&h),
        vec![
            [0x3fd22953041e1d58, 0x3fc785d93b6f6de2, 0x3fc785d93b6f6de2],
            [0x3fed51bce45757bb, 0x3fea1e89b1242488, 0x3fea1e89b1242488]
        ]
    );
}

#[test]
fn pinned_prism_coverage() {
    let open = [[0.5, 2.0, 1.0], [0.5, 7.0, 2.0], [7.0, 2.5, 3.0]];
    let close = [[0.5, 7.0, 4.0], [6.5, 0.5, 5.0], [2.5, 1.5, 6.0]];
    let p = Prism::from_arrays(open, close);
    let b: Vec<[u64; 8]> = p
        .coverage(4.5f64, 2.5)
        .iter()
        .map(|s| {
            [
                s.t0, s.t1, s.depth0, s.depth1, s.uv0[0], s.uv0[1], s.uv1[0], s.uv1[1],
            ]
            .map(f64::to_bits)
        })
        .collect();
    assert_eq!(
        b,
        vec![
            [
                0x0,
                0x3fc9999999999998,
                0x4002276276276276,
                0x40083a83a83a83a8,
                0x3fa3b13b13b13b14,
                0x3fe3b13b13b13b14,
                0x0,
                0x3fe6db6db6db6db6
            ],
            [
                0x3fd1c71c71c71c74,
                0x3fde18525b38ce92,
                0x400adb6db6db6db8,
                0x4010a8f1c052e61e,
                0x0,
                0x3fe8618618618619,
                0x3fcf73b618f813c8,
                0x3fe8231279c1fb0e
            ],
            [
                0x3fe5b7ec9bebc449,
                0x3fe9999999999988,
                0x40109b05b929e772,
                0x4010eeeeeeeeeeeb,
                0x3fec4f980a741150,
                0x3fbd833fac5f7580,
                0x3feaaaaaaaaaaabd,
                0x0
            ],
            [
                0x3feaaaaaaaaaaa9a,
                0x3ff0000000000000,
                0x401133333333332f,
                0x4013000000000000,
                0x3fe99999999999a8,
                0x0,
                0x3fe4cccccccccccd,
                0x3fa999999999999a
            ]
        ]
    );
    let p = Prism::from_arrays(
        open.map(|v| v.map(|x| x as f32)),
        close.map(|v| v.map(|x| x as f32)),
    );
    let b: Vec<[u32; 8]> = p
        .coverage(4.5f32, 2.5)
        .iter()
        .map(|s| {
            [
                s.t0, s.t1, s.depth0, s.depth1, s.uv0[0], s.uv0[1], s.uv1[0], s.uv1[1],
            ]
            .map(f32::to_bits)
        })
        .collect();
    assert_eq!(
        b,
        vec![
            [
                0x0, 0x3e4ccccd, 0x40113b14, 0x4041d41d, 0x3d1d89d9, 0x3f1d89d9, 0x0, 0x3f36db6e
            ],
            [
                0x3e8e38e2, 0x3ef0c294, 0x4056db6d, 0x4085478e, 0x0, 0x3f430c30, 0x3e7b9db4,
                0x3f411893
            ],
            [
                0x3f2dbf65, 0x3f4ccccd, 0x4084d82e, 0x40877778, 0x3f627cc0, 0x3dec19fe, 0x3f555555,
                0x0
            ],
            [
                0x3f555555, 0x3f800000, 0x4089999a, 0x40980000, 0x3f4ccccd, 0x0, 0x3f266667,
                0x3d4ccccd
            ]
        ]
    );
}
