//! The validated problem: specimen, mechanism (m), torsion factor k and options.

use serde::{Deserialize, Serialize};

use crate::error::{err, CornerError};
use crate::{Options, Specimen};

/// The mechanism family.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Mechanism {
    /// m = 0: pure rocking-sliding; each wall moves as one block.
    RockingSliding,
    /// m = 1: horizontal flexure; the out-of-plane wall splits into a green part and a red triangle.
    Flexural,
}

impl Mechanism {
    /// From the paper's flag m (0 or 1).
    pub fn from_m(m: u32) -> Result<Self, CornerError> {
        match m {
            0 => Ok(Mechanism::RockingSliding),
            1 => Ok(Mechanism::Flexural),
            _ => Err(err(
                "m",
                format!("must be 0 (rocking-sliding) or 1 (flexural), got {m}"),
            )),
        }
    }

    pub fn m(self) -> u32 {
        match self {
            Mechanism::RockingSliding => 0,
            Mechanism::Flexural => 1,
        }
    }
}

/// A validated problem: the corner, the mechanism, the torsion factor and the options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerModel {
    pub specimen: Specimen,
    pub mechanism: Mechanism,
    /// Reduction of the torsional contact at uplifted hinges, in [0, 1] (the paper: 0.3 to 0.6).
    pub k: f64,
    pub options: Options,
}

impl CornerModel {
    pub fn new(specimen: Specimen, m: u32, k: f64, options: Options) -> Result<Self, CornerError> {
        specimen.validate()?;
        let mechanism = Mechanism::from_m(m)?;
        // Each wall must hold at least one joint-aligned part: a base of whole half blocks
        // reaching t, plus one half block of red width under flexure.
        let base_units = (specimen.t / specimen.v() - 1e-9).ceil().max(1.0);
        let least = (base_units + f64::from(mechanism.m())) * specimen.v();
        for (name, length) in [
            ("blocks_x", specimen.length_x()),
            ("blocks_y", specimen.length_y()),
        ] {
            if length < least - 1e-12 {
                return Err(err(
                    name,
                    format!(
                        "the wall ({length} m) cannot hold a macroblock of m = {}: it needs {least} m",
                        mechanism.m()
                    ),
                ));
            }
        }
        if !(k.is_finite() && (0.0..=1.0).contains(&k)) {
            return Err(err("k", format!("must be in [0, 1], got {k}")));
        }
        Ok(CornerModel {
            specimen,
            mechanism,
            k,
            options,
        })
    }

    /// The paper's specimen and preset with the given m and k.
    pub fn paper(m: u32, k: f64) -> Result<Self, CornerError> {
        Self::new(Specimen::paper(), m, k, Options::default())
    }
}
