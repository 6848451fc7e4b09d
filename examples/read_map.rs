//! Peak memory of reading a height map: `read_map FILE` reads the map (format by content) into
//! a height map in metres and prints its grid and RMS height; run it under `/usr/bin/time -v`.
//! `read_map --write DIR N` first writes N × N maps as `map.gsf`, `map.sur` and `map.gwy` into
//! DIR (the files of the `read 4096x4096` benchmarks in benches/surface.rs).

#[path = "../benches/maps/mod.rs"]
mod maps;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--write") {
        let dir = std::path::Path::new(args.get(1).ok_or("--write DIR N")?);
        let n: usize = args.get(2).ok_or("--write DIR N")?.parse()?;
        std::fs::create_dir_all(dir)?;
        std::fs::write(dir.join("map.gsf"), maps::gsf(n))?;
        std::fs::write(dir.join("map.sur"), maps::sur(n))?;
        std::fs::write(dir.join("map.gwy"), maps::gwy(n))?;
        return Ok(());
    }
    let file = args
        .first()
        .ok_or("usage: read_map FILE | read_map --write DIR N")?;
    let map = adhesion::surface::io::read_height_map(std::path::Path::new(file), None)?;
    let n = map.z.len() as f64;
    let mean = map.z.iter().sum::<f64>() / n;
    let rms = (map.z.iter().map(|z| (z - mean) * (z - mean)).sum::<f64>() / n).sqrt();
    println!("{} x {} points, RMS height {rms:e} m", map.nx, map.ny);
    Ok(())
}
