//! Height-map files built for the reading benchmarks (`benches/surface.rs`) and the reading
//! example (`examples/read_map.rs`): `n` × `n` maps as Gwyddion simple field (f32), Digital Surf
//! `.sur` (int32, the header of the fixture sur-3.sur) and Gwyddion `.gwy` (f64).

/// Heights as stored integers: a smooth pattern (the values do not change the reading's work).
pub fn stored(k: usize) -> i32 {
    ((k * 7919) % 20_011) as i32 - 10_000
}

/// A fixture's bytes.
pub fn fixture(name: &str) -> Vec<u8> {
    std::fs::read(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures/maps")
            .join(name),
    )
    .expect("fixture")
}

/// Gwyddion simple field, 10 µm square.
pub fn gsf(n: usize) -> Vec<u8> {
    let mut gsf =
        format!("Gwyddion Simple Field 1.0\nXRes = {n}\nYRes = {n}\nXReal = 1e-05\nYReal = 1e-05\n")
            .into_bytes();
    gsf.extend(std::iter::repeat_n(0u8, 4 - gsf.len() % 4));
    gsf.reserve(4 * n * n);
    gsf.extend((0..n * n).flat_map(|k| (stored(k) as f32 * 1e-12).to_le_bytes()));
    gsf
}

/// Digital Surf `.sur` with int32 heights.
pub fn sur(n: usize) -> Vec<u8> {
    let mut sur = fixture("sur-3.sur")[..512].to_vec();
    sur[108..112].copy_from_slice(&(n as i32).to_le_bytes());
    sur[112..116].copy_from_slice(&(n as i32).to_le_bytes());
    sur[116..120].copy_from_slice(&((n * n) as u32).to_le_bytes());
    sur.reserve(4 * n * n);
    sur.extend((0..n * n).flat_map(|k| stored(k).to_le_bytes()));
    sur
}

/// Gwyddion `.gwy`: a container with one data field `/0/data` (f64 heights in metres).
pub fn gwy(n: usize) -> Vec<u8> {
    fn object(name: &str, components: &[u8]) -> Vec<u8> {
        let mut o = format!("{name}\0").into_bytes();
        o.extend((components.len() as u32).to_le_bytes());
        o.extend_from_slice(components);
        o
    }
    fn component(name: &str, kind: u8, value: &[u8]) -> Vec<u8> {
        let mut c = format!("{name}\0").into_bytes();
        c.push(kind);
        c.extend_from_slice(value);
        c
    }
    let unit = object("GwySIUnit", &component("unitstr", b's', b"m\0"));
    let mut data = ((n * n) as u32).to_le_bytes().to_vec();
    data.reserve(8 * n * n);
    data.extend((0..n * n).flat_map(|k| (f64::from(stored(k)) * 1e-12).to_le_bytes()));
    let field = object(
        "GwyDataField",
        &[
            component("xres", b'i', &(n as i32).to_le_bytes()),
            component("yres", b'i', &(n as i32).to_le_bytes()),
            component("xreal", b'd', &1e-5f64.to_le_bytes()),
            component("yreal", b'd', &1e-5f64.to_le_bytes()),
            component("si_unit_xy", b'o', &unit),
            component("si_unit_z", b'o', &unit),
            component("data", b'D', &data),
        ]
        .concat(),
    );
    let container = object(
        "GwyContainer",
        &[
            component("/0/data", b'o', &field),
            component("/0/data/title", b's', b"Height\0"),
        ]
        .concat(),
    );
    [b"GWYP".to_vec(), container].concat()
}
