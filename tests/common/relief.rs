//! Rough relief for terrain tests, shared by the library's and the command line's
//! tests (the latter include this file by path): value noise of five octaves, two of
//! them folded into ridges, and three cliffs (steps along random lines).

/// The noise and cliffs of one relief, drawn from a generator of uniform numbers in
/// [0, 1).
pub struct RoughRelief {
    /// Per octave: its cells per side and its `(cells + 2)²` lattice values.
    octaves: Vec<(usize, Vec<f64>)>,
    /// Per cliff: a point `(u, v)` on its line, the line's normal angle, its height.
    cliffs: Vec<[f64; 4]>,
}

impl RoughRelief {
    /// Five octaves of `coarsest << o` cells per side, then three cliffs of heights
    /// `lowest` to `lowest + range`, each drawn from `next`.
    pub fn new(
        mut next: impl FnMut() -> f64,
        coarsest: usize,
        (lowest, range): (f64, f64),
    ) -> Self {
        let octaves = (0..5)
            .map(|o| {
                let s = coarsest << o;
                (s, (0..(s + 2) * (s + 2)).map(|_| next()).collect())
            })
            .collect();
        let cliffs = (0..3)
            .map(|_| {
                let (u, v, angle) = (next(), next(), std::f64::consts::TAU * next());
                [u, v, angle, lowest + range * next()]
            })
            .collect();
        RoughRelief { octaves, cliffs }
    }

    /// The height at `(u, v)` in the unit square: the octaves from `amplitude` down,
    /// halving each time, plus the cliffs whose side the point is on.
    pub fn height(&self, u: f64, v: f64, amplitude: f64) -> f64 {
        let mut z = 0.0;
        let mut amplitude = amplitude;
        for (o, (s, values)) in self.octaves.iter().enumerate() {
            let (fx, fy) = (u * *s as f64, v * *s as f64);
            let (i, j) = (fx.floor() as usize, fy.floor() as usize);
            let smooth = |t: f64| t * t * (3.0 - 2.0 * t);
            let (tx, ty) = (smooth(fx - i as f64), smooth(fy - j as f64));
            let at = |a: usize, b: usize| values[b.min(s + 1) * (s + 2) + a.min(s + 1)];
            let n = at(i, j) * (1.0 - tx) * (1.0 - ty)
                + at(i + 1, j) * tx * (1.0 - ty)
                + at(i, j + 1) * (1.0 - tx) * ty
                + at(i + 1, j + 1) * tx * ty;
            // Octaves 1 and 2 folded into ridges.
            z += amplitude
                * if o == 1 || o == 2 {
                    1.0 - (2.0 * n - 1.0).abs()
                } else {
                    n
                };
            amplitude *= 0.5;
        }
        for &[cx, cy, angle, height] in &self.cliffs {
            if (u - cx) * angle.cos() + (v - cy) * angle.sin() > 0.0 {
                z += height;
            }
        }
        z
    }
}
