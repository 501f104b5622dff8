//! The record: rows, the shear's summary, CSV, and step timing.

use super::protocol::Host;
use super::specimen::Specimen;
use super::stress::Stress;
use super::{ShearRun, dem_engine};
use crate::SceneError;

/// One row of the record (SI units; stresses compression positive).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TriaxialRow {
    /// Axial strain `(H0 - H) / H0` [-].
    pub axial_strain: f64,
    /// Volumetric strain `(V0 - V) / V0` [-] (compression positive).
    pub volumetric_strain: f64,
    /// Stress ratio `q / p` from the walls [-].
    pub q_over_p: f64,
    /// Mean stress from the walls \[Pa\].
    pub p: f64,
    /// Deviatoric stress from the walls \[Pa\].
    pub q: f64,
    /// Axial wall stress `sigma_1` \[Pa\].
    pub sigma_axial: f64,
    /// Mean lateral wall stress `sigma_3` \[Pa\].
    pub sigma_lateral: f64,
    /// Mean stress from the contacts (Love-Weber) \[Pa\].
    pub p_contacts: f64,
    /// Deviatoric stress from the contacts \[Pa\].
    pub q_contacts: f64,
    /// Touching ball-ball contacts.
    pub contacts: usize,
    /// Mean coordination number (ball-ball contacts per ball, times 2) [-].
    pub coordination: f64,
    /// Share of the ball-ball contacts at the Coulomb limit [-].
    pub share_sliding: f64,
    /// Share of the ball-ball contacts rolling more than sliding (`|v_roll| > |v_disp|`) [-].
    pub share_rolling: f64,
    /// Share of the ball-ball contacts whose creep displacement in the step is at least
    /// [`CREEPING`](super::CREEPING) of their sliding displacement [-].
    pub share_creeping: f64,
    /// Solid fraction [-].
    pub solid_fraction: f64,
    /// Kinetic energy of the balls \[J\].
    pub kinetic_energy: f64,
}

pub(super) fn row<E: Host>(s: &E, st: &Stress, eps_a: f64, v0: f64, solids: f64) -> TriaxialRow {
    let v = st.dims[0] * st.dims[1] * st.dims[2];
    let sigma_1 = st.walls[1];
    let sigma_3 = 0.5 * (st.walls[0] + st.walls[2]);
    let p = (sigma_1 + 2.0 * sigma_3) / 3.0;
    let q = sigma_1 - sigma_3;
    let l = st.love;
    let p_c = (l[0][0] + l[1][1] + l[2][2]) / 3.0;
    let q_c = l[1][1] - 0.5 * (l[0][0] + l[2][2]);
    let (n, sliding, rolling, creeping) = s.contact_shares();
    let share = |k: usize| if n > 0 { k as f64 / n as f64 } else { 0.0 };
    TriaxialRow {
        axial_strain: eps_a,
        volumetric_strain: (v0 - v) / v0,
        q_over_p: q / p,
        p,
        q,
        sigma_axial: sigma_1,
        sigma_lateral: sigma_3,
        p_contacts: p_c,
        q_contacts: q_c,
        contacts: n,
        coordination: 2.0 * n as f64 / s.len() as f64,
        share_sliding: share(sliding),
        share_rolling: share(rolling),
        share_creeping: share(creeping),
        solid_fraction: solids / v,
        kinetic_energy: s.kinetic_energy(),
    }
}

/// What a shear shows, in the numbers the talk's conclusion is about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearSummary {
    /// Peak stress ratio `q / p` [-].
    pub peak_q_over_p: f64,
    /// Axial strain at the peak [-].
    pub peak_axial_strain: f64,
    /// Peak friction angle `asin((s1 - s3)/(s1 + s3))` \[deg\].
    pub peak_friction_angle_deg: f64,
    /// Largest dilatancy rate `-d eps_v / d eps_a` (over 1 % strain windows) [-].
    pub max_dilatancy_rate: f64,
    /// Dilatancy angle at that rate, `asin(D / (2 + D))` \[deg\].
    pub dilatancy_angle_deg: f64,
    /// Volumetric strain at the end [-].
    pub final_volumetric_strain: f64,
    /// Stress ratio at the end [-].
    pub final_q_over_p: f64,
    /// Mean shares of sliding, rolling and creeping contacts after 1 % strain [-].
    pub mean_shares: [f64; 3],
}

impl ShearRun {
    /// The peak friction angle, the dilatancy and the contact shares (module docs).
    pub fn summary(&self) -> ShearSummary {
        let peak = self
            .rows
            .iter()
            .copied()
            .max_by(|a, b| a.q_over_p.total_cmp(&b.q_over_p))
            .unwrap_or_default();
        let phi = ((peak.sigma_axial - peak.sigma_lateral)
            / (peak.sigma_axial + peak.sigma_lateral))
            .asin()
            .to_degrees();
        let mut d_max = f64::NEG_INFINITY;
        for (i, a) in self.rows.iter().enumerate() {
            if let Some(b) = self.rows[i..]
                .iter()
                .find(|b| b.axial_strain >= a.axial_strain + 0.01)
            {
                let d = -(b.volumetric_strain - a.volumetric_strain)
                    / (b.axial_strain - a.axial_strain);
                d_max = d_max.max(d);
            }
        }
        let late: Vec<&TriaxialRow> = self.rows.iter().filter(|r| r.axial_strain > 0.01).collect();
        let mean = |f: &dyn Fn(&TriaxialRow) -> f64| {
            if late.is_empty() {
                0.0
            } else {
                late.iter().map(|r| f(r)).sum::<f64>() / late.len() as f64
            }
        };
        let last = self.rows.last().copied().unwrap_or_default();
        ShearSummary {
            peak_q_over_p: peak.q_over_p,
            peak_axial_strain: peak.axial_strain,
            peak_friction_angle_deg: phi,
            max_dilatancy_rate: d_max,
            dilatancy_angle_deg: (d_max / (2.0 + d_max)).asin().to_degrees(),
            final_volumetric_strain: last.volumetric_strain,
            final_q_over_p: last.q_over_p,
            mean_shares: [
                mean(&|r| r.share_sliding),
                mean(&|r| r.share_rolling),
                mean(&|r| r.share_creeping),
            ],
        }
    }
}

/// The CSV header of [`TriaxialRow::csv`].
pub const CSV_HEADER: &str = "axial_strain,volumetric_strain,q_over_p,p,q,sigma_axial,sigma_lateral,p_contacts,q_contacts,contacts,coordination,share_sliding,share_rolling,share_creeping,solid_fraction,kinetic_energy";

impl TriaxialRow {
    /// The row as CSV (see [`CSV_HEADER`]).
    pub fn csv(&self) -> String {
        format!(
            "{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.4},{:.5},{:.5},{:.5},{:.6},{:.4e}",
            self.axial_strain,
            self.volumetric_strain,
            self.q_over_p,
            self.p,
            self.q,
            self.sigma_axial,
            self.sigma_lateral,
            self.p_contacts,
            self.q_contacts,
            self.contacts,
            self.coordination,
            self.share_sliding,
            self.share_rolling,
            self.share_creeping,
            self.solid_fraction,
            self.kinetic_energy
        )
    }
}

/// Wall-clock seconds of each of `steps` steps of [`Specimen::at_rest`] (the speed measure of
/// `creep bench dem`).
pub fn time_compliant_steps(
    specimen: &Specimen,
    creep: bool,
    steps: usize,
) -> Result<Vec<f64>, SceneError> {
    let mut s = specimen.at_rest(creep)?;
    let mut times = Vec::with_capacity(steps);
    for _ in 0..steps {
        let t = std::time::Instant::now();
        s.step_at_rest()?;
        times.push(t.elapsed().as_secs_f64());
    }
    Ok(times)
}

/// Wall-clock seconds of each of `steps` steps of [`Specimen::plain_rapier`].
pub fn time_plain_rapier_steps(specimen: &Specimen, steps: usize) -> Vec<f64> {
    let mut p = specimen.plain_rapier();
    (0..steps)
        .map(|_| {
            let t = std::time::Instant::now();
            p.step();
            t.elapsed().as_secs_f64()
        })
        .collect()
}

/// Wall-clock seconds of each of `steps` steps of the packing at rest in the creep-dem engine
/// ([`dem_engine`], the balls' friction on), on `threads` threads (1: the serial force loop;
/// more: rayon's, which needs creep-dem's `parallel` feature).
pub fn time_dem_steps<T: creep_dem::TangentialLaw>(
    specimen: &Specimen,
    creep: bool,
    threads: usize,
    steps: usize,
) -> Result<Vec<f64>, SceneError> {
    let run = || -> Result<Vec<f64>, SceneError> {
        let mut d = dem_engine::<T>(specimen, creep, threads > 1)?;
        let mut times = Vec::with_capacity(steps);
        for _ in 0..steps {
            let t = std::time::Instant::now();
            d.step()
                .map_err(|e| SceneError::Parameter(format!("DEM engine: {e}")))?;
            times.push(t.elapsed().as_secs_f64());
        }
        Ok(times)
    };
    if threads <= 1 {
        return run();
    }
    creep_dem::with_threads(threads, run)
        .map_err(|e| SceneError::Parameter(format!("DEM engine: {e}")))?
}
