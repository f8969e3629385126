//! A generated 3D surfacing program (raster passes of short G01 moves with a varying Z, as CAM
//! writes them), shared by the native and the wasm parse benchmarks.

/// About `bytes` of Fanuc-style surfacing G-code.
pub fn surfacing_program(bytes: usize) -> String {
    let mut text = String::with_capacity(bytes + 64);
    text.push_str("%\nO1000 (SURFACING)\nG90 G21 G17 G54\nG00 X0. Y0. Z5.\nG01 Z0. F1500.\n");
    let mut n = 0u32;
    while text.len() < bytes {
        let x = f64::from(n % 400) * 0.25;
        let y = f64::from(n / 400) * 0.5;
        let z = -((x * 0.07).sin() * (y * 0.05).cos()).abs() * 3.0;
        text.push_str(&format!(
            "N{} G01 X{x:.3} Y{y:.3} Z{z:.4}\n",
            n % 99_999 + 1
        ));
        n += 1;
    }
    text.push_str("M30\n%\n");
    text
}
