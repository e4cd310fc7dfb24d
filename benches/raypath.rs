fn main() {
    let env = atm_refraction::Environment {
        shape: atm_refraction::EarthShape::Spherical { radius: 6_371_000.0 },
        atmosphere: atm_refraction::air::us76_atmosphere(),
        wavelength: 530e-9,
    };
    println!("{}", env.n(0.0));
}
