//! Issue 18, item 3: the tabulated index of an atmosphere of height alone. The table's error is
//! within its stated bound (`morgana::atmosphere::radial_table`: relative ε = rtol of q and
//! q′, with floors of 10⁻⁶ of the sea-level q and 10⁻³ of its scale q₀/8 km) at 10⁵ random heights, against the exact
//! atmosphere, for USA76 with Ciddor and with Cauchy dispersion and for the hot road (30 K at the
//! ground decaying over 6.667 m), whose knots crowd at the ground; and n, ∇n from the table
//! agree with the atmosphere's own at random points and wavelengths within K(λ) times that bound.
//!
//!   cargo test --release --test radial_table

use glam::DVec3;
use morgana::atmosphere::edit::{Edit, HotSurface};
use morgana::atmosphere::{AirDispersion, Atmosphere, RadialTable};

/// The integrator's default rtol.
const EPSILON: f64 = 1e-9;

/// A xorshift generator: uniform numbers in [0, 1).
struct Uniform(u64);

impl Uniform {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn atmospheres() -> Vec<(&'static str, Atmosphere)> {
    let usa76 = Atmosphere::usa76();
    let cauchy = Atmosphere::new(
        "usa76 cauchy",
        usa76.earth,
        usa76.base.clone(),
        Vec::new(),
        AirDispersion::CauchyBornWolf,
        usa76.top_m(),
    )
    .expect("valid");
    let hot = HotSurface::new(30.0, 6.667).expect("valid edit");
    let hot_road = Atmosphere::new(
        "hot road",
        usa76.earth,
        usa76.base.clone(),
        vec![Edit::HotSurface(hot)],
        usa76.dispersion,
        usa76.top_m(),
    )
    .expect("valid");
    vec![("usa76", usa76), ("usa76 cauchy", cauchy), ("hot road", hot_road)]
}

#[test]
fn the_table_is_within_its_bound_at_100000_random_heights() {
    let mut u = Uniform(0x9e37_79b9_7f4a_7c15);
    for (name, atm) in atmospheres() {
        let table = RadialTable::new(&atm, EPSILON).expect("tabulated");
        let (mut worst_q, mut worst_dq) = (0.0f64, 0.0f64);
        for i in 0..100_000 {
            // Half uniform over the table (−5 km to the top), half log-uniform in 1 mm – 1 km
            // above the ground, where a hot road's layer is.
            let h = if i % 2 == 0 {
                -5000.0 + u.next() * (atm.top_m() + 5000.0)
            } else {
                10f64.powf(-3.0 + 6.0 * u.next())
            };
            let (q, dq) = atm.reduced_refractivity(h);
            let (tq, tdq) = table.at(h).expect("inside the table");
            let (bq, bdq) = table.bound(q, dq);
            worst_q = worst_q.max((tq - q).abs() / bq);
            worst_dq = worst_dq.max((tdq - dq).abs() / bdq);
            assert!((tq - q).abs() <= bq, "{name} at {h} m: q {tq} against {q} (bound {bq})");
            assert!((tdq - dq).abs() <= bdq, "{name} at {h} m: q′ {tdq} against {dq} (bound {bdq})");
        }
        eprintln!(
            "{name}: {} intervals; worst error {worst_q:.3} of the bound in q, {worst_dq:.3} in q′",
            table.intervals()
        );
    }
}

#[test]
fn n_and_its_gradient_from_the_table_match_the_atmosphere() {
    let mut u = Uniform(0x2545_f491_4f6c_dd1d);
    for (name, atm) in atmospheres() {
        let table = RadialTable::new(&atm, EPSILON).expect("tabulated");
        for _ in 0..20_000 {
            let lambda = 380.0 + 400.0 * u.next();
            // Points up to 100 km away horizontally, −100 m to 90 km up, in the atmosphere's frame.
            let p = DVec3::new(2e5 * (u.next() - 0.5), -100.0 + 9.01e4 * u.next(), 2e5 * (u.next() - 0.5));
            let (n, g) = atm.n_grad(lambda, p);
            let k = table.k(lambda);
            let (tn, tg) = table.n_grad(k, lambda, p);
            let h = atm.earth.height(p);
            let (q, dq) = atm.reduced_refractivity(h);
            let (bq, bdq) = table.bound(q, dq);
            // The table's bound times K, and the rounding of n = 1 + K·q: two units in the last place.
            assert!((tn - n).abs() <= k * bq + 4.5e-16, "{name} at {p} ({h} m), {lambda} nm: n {tn} against {n}");
            assert!(
                (tg - g).length() <= k * bdq + 1e-16 * g.length() + 1e-30,
                "{name} at {p} ({h} m), {lambda} nm: ∇n {tg} against {g}"
            );
        }
    }
}
