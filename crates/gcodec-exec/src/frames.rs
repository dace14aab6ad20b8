//! Frames: the programmable frame (`TRANS`, `AROT`, `SCALE`, `MIRROR`, …),
//! frame values and their functions (`CTRANS(X,10):CROT(Z,45)`), and the
//! coordinate transformation of a frame and of a chain of frames (SPEC
//! §11.x "Frames"; reference §9 and §6).
//!
//! Everything here is a pure function of plain numbers: the channel
//! evaluates the values of a frame instruction, resolves the axes to
//! indices of [`FrameAxes`] and calls [`Frame::apply`]; it composes the
//! chain of §9.2 with [`Frame::chain`] and maps positions with
//! [`Frame::to_outer`] / [`Frame::to_inner`]. Errors are [`RunError`]s
//! (code [`codes::run::FRAME`] for what frames reject), never panics.
//!
//! # The frame and its order
//!
//! A frame holds, per channel axis, a coarse translation (`TR`), a fine
//! translation (`FI`), a scale (`SC`) and a mirroring (`MI`), and one
//! rotation of the geometry axes (`RT` of X, Y, Z: RPY angles in degrees,
//! MD10600 = 1). It maps a point `p` of its inner (workpiece) system to its
//! outer system as
//!
//! ```text
//! outer = T + R · (S · M · p)        T = TR + FI, R rotation, S scale, M ±1
//! ```
//!
//! i.e. translation, then rotation, then scale, then mirroring (the
//! control's K2 formula). Axes that are no geometry axes (rotary axes,
//! special axes) take translation, scale and mirroring, never rotation.
//!
//! # Substituting and additive instructions
//!
//! `TRANS`, `ROT`, `SCALE`, `MIRROR` first reset the whole programmable
//! frame (all components of all axes) and then set their own; the bare
//! keyword resets. `ATRANS`, `AROT`, `ASCALE`, `AMIRROR` act in the frame's
//! own (rotated, scaled, mirrored) system: the frame becomes `frame :
//! instruction` ([`Frame::chain`]). So `ATRANS` after `ROT Z45` moves along
//! the rotated axes, `ATRANS` after `SCALE X2` is scaled, `AROT` composes
//! rotations, `ASCALE` multiplies scales and `AMIRROR` toggles.
//!
//! # Geometry slots
//!
//! Rotations act on the frame's X, Y and Z ("slots" 0, 1, 2). A geometry
//! axis named `X`, `Y` or `Z` takes that slot; the other geometry axes take
//! the free slots in ascending order. A lathe with the geometry axes X and
//! Z thus has no Y slot: a rotation that would move the missing axis
//! (`ROT RPL=30` under `G17`) is rejected, one in its Z/X plane (`G18`)
//! works.

use std::sync::Arc;

use gcodec_lang::FrameOp;
use gcodec_lang::functions::Function;
use gcodec_profile::Profile;
use gcodec_source::codes;

use crate::geometry::Plane;
use crate::value::{FrameAxis, FrameValue, RtValue, RunError};

type Mat3 = [[f64; 3]; 3];

const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The frame's names for the geometry slots.
const SLOT_NAMES: [&str; 3] = ["X", "Y", "Z"];

// ---------------------------------------------------------------------
// Axes

/// The channel's axes as frames see them: the names in the profile's order
/// and which of them are geometry axes, each with its slot (the frame's X,
/// Y or Z for rotations; see the module documentation).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FrameAxes {
    /// Upper case.
    names: Vec<Arc<str>>,
    /// Per axis its geometry slot.
    slot_of: Vec<Option<usize>>,
    /// Per slot its axis.
    axis_of: [Option<usize>; 3],
}

impl FrameAxes {
    /// The axes from `(name, is_geometry)` in channel order. Only the first
    /// three geometry axes are geometry axes (a channel has at most three);
    /// a further one is treated as a special axis.
    pub fn new<S: AsRef<str>>(axes: impl IntoIterator<Item = (S, bool)>) -> Self {
        let mut names = Vec::new();
        let mut geometry = Vec::new();
        for (name, is_geometry) in axes {
            names.push(Arc::from(name.as_ref().to_ascii_uppercase().as_str()));
            if is_geometry && geometry.len() < 3 {
                geometry.push(names.len() - 1);
            }
        }
        let mut slot_of = vec![None; names.len()];
        let mut axis_of = [None; 3];
        // A geometry axis named X, Y or Z takes its own slot …
        for &i in &geometry {
            if let Some(s) = SLOT_NAMES.iter().position(|n| **n == *names[i])
                && axis_of[s].is_none()
            {
                axis_of[s] = Some(i);
                slot_of[i] = Some(s);
            }
        }
        // … the others the free slots in ascending order.
        for &i in &geometry {
            if slot_of[i].is_none()
                && let Some(s) = (0..3).find(|&s| axis_of[s].is_none())
            {
                axis_of[s] = Some(i);
                slot_of[i] = Some(s);
            }
        }
        Self {
            names,
            slot_of,
            axis_of,
        }
    }

    /// The axes of a machine profile (`[[axes]]` with `geometry`).
    pub fn from_profile(profile: &Profile) -> Self {
        Self::new(
            profile
                .axes
                .iter()
                .map(|a| (a.name.get_ref().as_str(), a.geometry)),
        )
    }

    /// The number of channel axes.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Whether there are no axes.
    pub fn is_empty(&self) -> bool {
        self.names.is_empty()
    }

    /// The name of axis `index` (upper case).
    pub fn name(&self, index: usize) -> Option<&str> {
        self.names.get(index).map(|n| &**n)
    }

    /// The index of the axis named `name` (any case).
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n.eq_ignore_ascii_case(name))
    }

    /// The geometry slot (0 X, 1 Y, 2 Z) of axis `index`; `None` for an
    /// axis that is no geometry axis.
    pub fn geometry_slot(&self, index: usize) -> Option<usize> {
        self.slot_of.get(index).copied().flatten()
    }

    /// The axis in geometry slot `slot` (0 X, 1 Y, 2 Z), if the machine has
    /// one.
    pub fn geometry_axis(&self, slot: usize) -> Option<usize> {
        self.axis_of.get(slot).copied().flatten()
    }
}

/// The error of a frame instruction the executor does not simulate (the
/// solid-angle rotations): the positions after it would be wrong.
pub fn not_simulated(op: FrameOp) -> RunError {
    RunError::new(
        codes::run::FRAME,
        format!(
            "`{}` is not simulated: the positions after it would be wrong",
            op.keyword()
        ),
    )
}

// ---------------------------------------------------------------------
// The frame

/// The components of one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
struct AxisPart {
    coarse: f64,
    fine: f64,
    scale: f64,
    mirror: bool,
}

impl AxisPart {
    const NEUTRAL: AxisPart = AxisPart {
        coarse: 0.0,
        fine: 0.0,
        scale: 1.0,
        mirror: false,
    };

    /// The total translation.
    fn offset(&self) -> f64 {
        self.coarse + self.fine
    }

    /// Scale times mirroring.
    fn factor(&self) -> f64 {
        if self.mirror { -self.scale } else { self.scale }
    }

    fn is_neutral(&self) -> bool {
        self.coarse == 0.0 && self.fine == 0.0 && self.scale == 1.0 && !self.mirror
    }
}

/// A rotation of the geometry slots: its RPY angles (X, Y, Z; degrees) and
/// the matrix `Rz(z)·Ry(y)·Rx(x)` they give. The angles are authoritative:
/// the matrix is always computed from them.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rotation {
    angles: [f64; 3],
    m: Mat3,
}

impl Rotation {
    const NONE: Rotation = Rotation {
        angles: [0.0; 3],
        m: IDENTITY,
    };

    fn from_angles(angles: [f64; 3]) -> Self {
        let m = mul(
            &mul(&axis_rotation(2, angles[2]), &axis_rotation(1, angles[1])),
            &axis_rotation(0, angles[0]),
        );
        Self { angles, m }
    }

    fn is_none(&self) -> bool {
        self.angles == [0.0; 3]
    }

    /// The only slot with an angle, if just one has one.
    fn single(&self) -> Option<usize> {
        let mut nonzero = (0..3).filter(|&s| self.angles[s] != 0.0);
        let s = nonzero.next()?;
        nonzero.next().is_none().then_some(s)
    }

    /// `self · inner`: `inner` acts first, in the system `self` rotated to.
    fn then(&self, inner: &Rotation) -> Rotation {
        if inner.is_none() {
            return *self;
        }
        if self.is_none() {
            return *inner;
        }
        match (self.single(), inner.single()) {
            // The angles as programmed: `ROT Z30` `AROT Z20` reads Z 50.
            (Some(a), Some(b)) if a == b => {
                let mut angles = [0.0; 3];
                angles[a] = self.angles[a] + inner.angles[a];
                Rotation::from_angles(angles)
            }
            _ => Rotation::from_matrix(&mul(&self.m, &inner.m)),
        }
    }

    /// The inverse rotation.
    fn inverse(&self) -> Rotation {
        match self.single() {
            None if self.is_none() => *self,
            Some(s) => {
                let mut angles = [0.0; 3];
                angles[s] = -self.angles[s];
                Rotation::from_angles(angles)
            }
            None => Rotation::from_matrix(&transpose(&self.m)),
        }
    }

    /// `D · R · D` with the diagonal ±1 matrix `D` of `mirror`: the
    /// rotation as it looks through a mirror. In RPY angles that flips the
    /// sign of the angle about an axis when exactly one of the two other
    /// axes is mirrored.
    fn mirrored(&self, mirror: [bool; 3]) -> Rotation {
        if mirror == [false; 3] || self.is_none() {
            return *self;
        }
        let sign = |b: bool| if b { -1.0 } else { 1.0 };
        let d = mirror.map(sign);
        let a = self.angles;
        Rotation::from_angles([a[0] * d[1] * d[2], a[1] * d[0] * d[2], a[2] * d[0] * d[1]])
    }

    /// The RPY angles of a rotation matrix (x, z in −180…180, y in
    /// −90…90; at y = ±90 x is 0), snapped to whole degrees within 1e-9.
    fn from_matrix(m: &Mat3) -> Rotation {
        let sy = (-m[2][0]).clamp(-1.0, 1.0);
        let y = sy.asin();
        let (x, z) = if y.cos() > 1e-9 {
            (m[2][1].atan2(m[2][2]), m[1][0].atan2(m[0][0]))
        } else {
            (0.0, (-m[0][1]).atan2(m[1][1]))
        };
        Rotation::from_angles([x, y, z].map(|a| snap_degrees(a.to_degrees())))
    }

    fn apply(&self, v: [f64; 3]) -> [f64; 3] {
        mul_vec(&self.m, v)
    }

    fn apply_inverse(&self, v: [f64; 3]) -> [f64; 3] {
        let m = &self.m;
        [
            m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2],
            m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
            m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2],
        ]
    }
}

/// A frame acting on the channel's axes: per axis a translation (coarse
/// plus fine), a scale and a mirroring; one rotation of the geometry axes
/// (a rotation matrix and the RPY angles it was programmed with, which read
/// back as the `RT` components). See the module documentation for the
/// order and the meaning of substituting and additive instructions.
///
/// A frame belongs to the [`FrameAxes`] it was made for: its vectors are
/// indexed like them.
#[derive(Clone, Debug)]
pub struct Frame {
    axes: Vec<AxisPart>,
    rotation: Rotation,
    /// Per geometry slot its axis index (copied from the [`FrameAxes`]).
    slots: [Option<usize>; 3],
    /// Which value this is: a new frame gets a new one, a clone keeps it.
    /// A frame is only changed while it is made (its fields are private,
    /// and `apply` replaces it whole), so frames of one id are equal.
    id: u64,
}

/// Which translation of a frame an axial offset replaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TranslationPart {
    /// `TR`, the coarse translation (`G58`, `TRANS`).
    Coarse,
    /// `FI`, the fine translation (`G59`).
    Fine,
}

/// Frames are equal by their contents, whatever their ids.
impl PartialEq for Frame {
    fn eq(&self, other: &Self) -> bool {
        self.axes == other.axes && self.rotation == other.rotation && self.slots == other.slots
    }
}

/// What an identity frame maps the finite values `point` out to, into
/// `out`: `0 + p` ([`Frame::to_outer`]), which is `p` but for `-0.0`,
/// which becomes `+0.0`.
pub(crate) fn identity_outward(point: &[f64], out: &mut [f64]) {
    for (o, p) in out.iter_mut().zip(point) {
        *o = 0.0 + p;
    }
}

/// Copies `point` to `out` if an identity frame maps each of its values
/// into itself as it is ([`Frame::to_inner`]: a finite value other than
/// `-0.0`, whose sign the rotation's `0 × v` terms can change); `false`,
/// with `out` partly written, otherwise.
pub(crate) fn identity_inward_as_is(point: &[f64], out: &mut [f64]) -> bool {
    for (o, &p) in out.iter_mut().zip(point) {
        if !p.is_finite() || p.to_bits() == (-0.0f64).to_bits() {
            return false;
        }
        *o = p;
    }
    true
}

/// A fresh [`Frame::id`].
fn frame_id() -> u64 {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
}

impl Frame {
    /// The neutral frame: no translation, rotation, scaling or mirroring.
    pub fn neutral(axes: &FrameAxes) -> Self {
        Self {
            axes: vec![AxisPart::NEUTRAL; axes.len()],
            rotation: Rotation::NONE,
            slots: axes.axis_of,
            id: frame_id(),
        }
    }

    /// Whether `other` is equal to this frame, at once when it is a clone
    /// of it (a motion asks twice whether the frames changed).
    pub fn same_as(&self, other: &Frame) -> bool {
        self.id == other.id || self == other
    }

    /// Whether every component is neutral (all translations 0, all angles
    /// 0, all scales 1, nothing mirrored).
    pub fn is_neutral(&self) -> bool {
        self.rotation.is_none() && self.axes.iter().all(AxisPart::is_neutral)
    }

    /// A pure (coarse) translation per axis: the settable work offsets
    /// `G54`… of the machine profile. `values` are (axis index, value).
    pub fn translation(axes: &FrameAxes, values: &[(usize, f64)]) -> Result<Frame, RunError> {
        check_values(axes, "TRANS", values)?;
        Ok(Frame::checked_translation(axes, values))
    }

    /// [`translation`](Self::translation) of values [`check_values`] passed.
    fn checked_translation(axes: &FrameAxes, values: &[(usize, f64)]) -> Frame {
        let mut f = Frame::neutral(axes);
        for &(i, v) in values {
            f.axes[i].coarse = v;
        }
        f
    }

    /// The coarse translation (`TR`) of axis `index` (0 outside the axes).
    pub fn coarse(&self, index: usize) -> f64 {
        self.part(index).coarse
    }

    /// The fine translation (`FI`) of axis `index`.
    pub fn fine(&self, index: usize) -> f64 {
        self.part(index).fine
    }

    /// The scale (`SC`) of axis `index` (1 outside the axes).
    pub fn scale(&self, index: usize) -> f64 {
        self.part(index).scale
    }

    /// Whether axis `index` is mirrored (`MI`).
    pub fn mirrored(&self, index: usize) -> bool {
        self.part(index).mirror
    }

    /// The RPY angles (degrees) about the frame's X, Y and Z: the `RT`
    /// components of the geometry slots.
    pub fn angles(&self) -> [f64; 3] {
        self.rotation.angles
    }

    /// The rotation matrix `Rz·Ry·Rx` of the geometry slots (row-major).
    pub fn rotation_matrix(&self) -> [[f64; 3]; 3] {
        self.rotation.m
    }

    fn part(&self, index: usize) -> AxisPart {
        self.axes.get(index).copied().unwrap_or(AxisPart::NEUTRAL)
    }

    /// Applies one frame instruction with evaluated values: `values` are
    /// (axis index, value); `rpl` is `RPL=` (degrees, a rotation in the
    /// active `plane`: `G17` about Z, `G18` about Y, `G19` about X) for
    /// `ROT`/`AROT`.
    ///
    /// `TRANS`, `ROT`, `SCALE`, `MIRROR` first reset the whole frame; with
    /// no values (and no `RPL=`) they only reset. The additive instructions
    /// act in the frame's own system (`self : instruction`); with no values
    /// they change nothing. Several angles in one `ROT` are RPY: Z, then
    /// Y', then X''. `MIRROR`/`AMIRROR` ignore the values (`MIRROR X0`
    /// mirrors X; `AMIRROR X0` toggles it). The solid-angle rotations
    /// (`ROTS`, `AROTS`, `CROTS`) are not simulated ([`not_simulated`]).
    ///
    /// On an error the frame is left as it was.
    pub fn apply(
        &mut self,
        axes: &FrameAxes,
        op: FrameOp,
        values: &[(usize, f64)],
        rpl: Option<f64>,
        plane: Plane,
    ) -> Result<(), RunError> {
        let keyword = op.keyword();
        check_values(axes, keyword, values)?;
        if let Some(r) = rpl {
            if !op.is_rotation() {
                return Err(RunError::new(
                    codes::run::FRAME,
                    format!("`{keyword}`: `RPL=` belongs to `ROT` and `AROT`"),
                ));
            }
            if !r.is_finite() {
                return Err(RunError::new(
                    codes::run::FRAME,
                    format!("`{keyword} RPL={r}`: the angle is not a finite number"),
                ));
            }
        }
        let step = match op {
            FrameOp::Trans | FrameOp::Atrans => Frame::checked_translation(axes, values),
            FrameOp::Rot | FrameOp::Arot => rotation_frame(axes, keyword, values, rpl, plane)?,
            FrameOp::Scale | FrameOp::Ascale => scale_frame(axes, keyword, values)?,
            FrameOp::Mirror | FrameOp::Amirror => {
                let mut f = Frame::neutral(axes);
                for &(i, _) in values {
                    f.axes[i].mirror = true;
                }
                f
            }
            FrameOp::Rots | FrameOp::Arots | FrameOp::Crots => return Err(not_simulated(op)),
        };
        let next = if op.is_additive() {
            self.chain(&step)
        } else {
            step
        };
        next.check(keyword)?;
        *self = next;
        Ok(())
    }

    /// `G58` (`part` coarse) or `G59` (fine): the translation of each axis
    /// of `values` (axis index, value) replaced, every other component
    /// kept. On an error the frame is left as it was.
    pub fn replace_translation(
        &mut self,
        axes: &FrameAxes,
        part: TranslationPart,
        values: &[(usize, f64)],
    ) -> Result<(), RunError> {
        let keyword = match part {
            TranslationPart::Coarse => "G58",
            TranslationPart::Fine => "G59",
        };
        check_values(axes, keyword, values)?;
        let mut next = self.clone();
        next.id = frame_id();
        for &(i, v) in values {
            match part {
                TranslationPart::Coarse => next.axes[i].coarse = v,
                TranslationPart::Fine => next.axes[i].fine = v,
            }
        }
        *self = next;
        Ok(())
    }

    /// The geometry slots that have an axis: (slot, axis index).
    fn geometry(&self) -> impl Iterator<Item = (usize, usize)> + use<> {
        let slots = self.slots;
        (0..3).filter_map(move |s| slots[s].map(|i| (s, i)))
    }

    /// Maps a point of this frame's inner (workpiece) system to its outer
    /// system: `T + R·(S·M·p)` for all axes. `point` and `out` are indexed
    /// like the [`FrameAxes`]; entries past the frame's axes are copied
    /// unchanged, entries past the shorter of the two slices are left out.
    /// Allocates nothing.
    pub fn to_outer(&self, point: &[f64], out: &mut [f64]) {
        let len = point.len().min(out.len());
        let n = self.axes.len().min(len);
        let finite = point[..n].iter().all(|v| v.is_finite());
        if finite && self.rotation.m == IDENTITY && self.axes_only_translate() {
            self.translation_to_outer(point, out, len, n);
        } else {
            self.general_to_outer(point, out, len, n);
        }
    }

    /// [`to_outer`](Self::to_outer) of a frame that only translates (a work
    /// offset, or none: [`Self::axes_only_translate`], the rotation the
    /// identity) and a finite point: `T + p` for every axis, as the general
    /// path gives it bit for bit. `1 × p` is `p`; the rotation adds `0 × v`
    /// of the other slots, signed zeros that leave a non-zero `p` as it is
    /// and change at most a zero's sign, and adding a translation that is
    /// not `-0.0` gives the same sum for either sign of a zero (`+0.0` for
    /// a zero under the identity). An infinite coordinate would make
    /// `0 × v` a NaN: such a point takes the general path.
    fn translation_to_outer(&self, point: &[f64], out: &mut [f64], len: usize, n: usize) {
        for ((o, p), axis) in out[..n].iter_mut().zip(&point[..n]).zip(&self.axes) {
            *o = axis.offset() + p;
        }
        out[n..len].copy_from_slice(&point[n..len]);
    }

    /// Whether no axis scales or mirrors, bit for bit, and none translates
    /// by `-0.0` (whose sum with a zero depends on the zero's sign):
    /// [`Self::translation_to_outer`] applies.
    fn axes_only_translate(&self) -> bool {
        self.axes.iter().all(|a| {
            a.scale.to_bits() == 1f64.to_bits()
                && !a.mirror
                && a.offset().to_bits() != (-0.0f64).to_bits()
        })
    }

    /// [`to_outer`](Self::to_outer) of any frame.
    fn general_to_outer(&self, point: &[f64], out: &mut [f64], len: usize, n: usize) {
        let mut g = [0.0; 3];
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            g[s] = self.axes[i].factor() * point[i];
        }
        let g = self.rotation.apply(g);
        for i in 0..n {
            let a = &self.axes[i];
            out[i] = a.offset() + a.factor() * point[i];
        }
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            out[i] = self.axes[i].offset() + g[s];
        }
        out[n..len].copy_from_slice(&point[n..len]);
    }

    /// The exact inverse of [`to_outer`](Self::to_outer): a point of the
    /// outer system in this frame's inner system, `M·S⁻¹·Rᵀ·(x − T)`.
    /// Allocates nothing.
    pub fn to_inner(&self, point: &[f64], out: &mut [f64]) {
        let len = point.len().min(out.len());
        let n = self.axes.len().min(len);
        if self.axes_exactly_neutral() {
            self.rotation_to_inner(point, out, len, n);
        } else {
            self.general_to_inner(point, out, len, n);
        }
    }

    /// [`to_inner`](Self::to_inner) of any frame.
    fn general_to_inner(&self, point: &[f64], out: &mut [f64], len: usize, n: usize) {
        let mut g = [0.0; 3];
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            g[s] = point[i] - self.axes[i].offset();
        }
        let g = self.rotation.apply_inverse(g);
        for i in 0..n {
            let a = &self.axes[i];
            out[i] = (point[i] - a.offset()) / a.factor();
        }
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            out[i] = g[s] / self.axes[i].factor();
        }
        out[n..len].copy_from_slice(&point[n..len]);
    }

    /// Whether no axis translates, scales or mirrors, bit for bit: `+0.0`
    /// translations and scales of exactly 1 (a `-0.0` translation is not
    /// neutral here: subtracting it turns `-0` into `+0`). Most blocks run
    /// in such a frame (no work offset, no programmable frame).
    fn axes_exactly_neutral(&self) -> bool {
        self.axes.iter().all(|a| {
            a.coarse.to_bits() == 0
                && a.fine.to_bits() == 0
                && a.scale.to_bits() == 1f64.to_bits()
                && !a.mirror
        })
    }

    /// Whether the frame changes no value: its axes exactly neutral and
    /// its rotation matrix the identity (ones on the diagonal, zeros of
    /// either sign elsewhere). Its arithmetic still turns a `-0.0` into
    /// `+0.0`, and a point with an infinite coordinate into NaNs.
    pub fn is_identity(&self) -> bool {
        self.rotation.m == IDENTITY && self.axes_exactly_neutral()
    }

    /// [`to_inner`](Self::to_inner) of a frame whose axes are exactly
    /// neutral: `p − (+0)` and `p / 1` are `p`, bit for bit, so only the
    /// rotation is computed, as in the general path: the identity still
    /// adds `0 × v` of the other slots, which decides the sign of a zero
    /// (the JSONL writes `-0.0`), and no `0 +` follows here.
    fn rotation_to_inner(&self, point: &[f64], out: &mut [f64], len: usize, n: usize) {
        let mut g = [0.0; 3];
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            g[s] = point[i];
        }
        let g = self.rotation.apply_inverse(g);
        out[..len].copy_from_slice(&point[..len]);
        for (s, i) in self.geometry().filter(|&(_, i)| i < n) {
            out[i] = g[s];
        }
    }

    /// The chained frame `self : inner` (`inner` acts inside `self`), as the
    /// `:` operator and the frame chain of §9.2 compose frames:
    /// `(self : inner).to_outer(p) = self.to_outer(inner.to_outer(p))`.
    ///
    /// Translations: `T = Tₛ + Rₛ·Sₛ·Mₛ·Tᵢ` (coarse and fine each);
    /// scales multiply, mirrorings toggle; the rotation is `Rₛ · (D·Rᵢ·D)`
    /// with `D` the mirroring of `self`. Exact when the scales of `self` are
    /// equal on the axes `inner` rotates (always for a rotation-free
    /// `inner`); with unequal scales the rotation is composed outside the
    /// scale, as the frame's components can only express that.
    pub fn chain(&self, inner: &Frame) -> Frame {
        let n = self.axes.len().max(inner.axes.len());
        let mut axes = Vec::with_capacity(n);
        for i in 0..n {
            let (a, b) = (self.part(i), inner.part(i));
            axes.push(AxisPart {
                coarse: a.coarse + a.factor() * b.coarse,
                fine: a.fine + a.factor() * b.fine,
                scale: a.scale * b.scale,
                mirror: a.mirror != b.mirror,
            });
        }
        // The geometry slots: the inner translations rotated.
        let mut coarse = [0.0; 3];
        let mut fine = [0.0; 3];
        let mut mirror = [false; 3];
        for (s, i) in self.geometry() {
            let (a, b) = (self.part(i), inner.part(i));
            coarse[s] = a.factor() * b.coarse;
            fine[s] = a.factor() * b.fine;
            mirror[s] = a.mirror;
        }
        let coarse = self.rotation.apply(coarse);
        let fine = self.rotation.apply(fine);
        for (s, i) in self.geometry() {
            let a = self.part(i);
            axes[i].coarse = a.coarse + coarse[s];
            axes[i].fine = a.fine + fine[s];
        }
        Frame {
            axes,
            rotation: self.rotation.then(&inner.rotation.mirrored(mirror)),
            slots: self.slots,
            id: frame_id(),
        }
    }

    /// The inverse frame (`INVFRAME`): `f.chain(&f.inverse())` is neutral.
    /// Exact under the same condition as [`chain`](Self::chain) (equal
    /// scales on the rotated axes).
    pub fn inverse(&self) -> Frame {
        let mut axes: Vec<AxisPart> = self
            .axes
            .iter()
            .map(|a| AxisPart {
                coarse: -a.coarse / a.factor(),
                fine: -a.fine / a.factor(),
                scale: 1.0 / a.scale,
                mirror: a.mirror,
            })
            .collect();
        let mut coarse = [0.0; 3];
        let mut fine = [0.0; 3];
        let mut mirror = [false; 3];
        for (s, i) in self.geometry() {
            let a = self.part(i);
            coarse[s] = a.coarse;
            fine[s] = a.fine;
            mirror[s] = a.mirror;
        }
        let coarse = self.rotation.apply_inverse(coarse);
        let fine = self.rotation.apply_inverse(fine);
        for (s, i) in self.geometry() {
            if let Some(a) = axes.get_mut(i) {
                let factor = self.axes[i].factor();
                a.coarse = -coarse[s] / factor;
                a.fine = -fine[s] / factor;
            }
        }
        Frame {
            axes,
            rotation: self.rotation.inverse().mirrored(mirror),
            slots: self.slots,
            id: frame_id(),
        }
    }

    /// The frame as a FRAME value: per axis with a non-neutral component
    /// (in channel order) `TR`, `FI`, `RT` (the geometry slot's angle, 0
    /// for other axes), `SC`, `MI`.
    pub fn to_value(&self, axes: &FrameAxes) -> FrameValue {
        let mut value = FrameValue::default();
        for (i, a) in self.axes.iter().enumerate() {
            let rotation = self
                .slots
                .iter()
                .position(|s| *s == Some(i))
                .map_or(0.0, |s| self.rotation.angles[s]);
            if a.is_neutral() && rotation == 0.0 {
                continue;
            }
            let name = axes.name(i).unwrap_or("");
            value.axes.push(FrameAxis {
                axis: Arc::from(name),
                // `+ 0.0` turns −0 into 0.
                translation: a.coarse + 0.0,
                fine: a.fine + 0.0,
                rotation: rotation + 0.0,
                scale: a.scale,
                mirror: a.mirror,
            });
        }
        value
    }

    /// A frame from a FRAME value. Every axis with a non-neutral component
    /// must be a channel axis ([`codes::run::UNKNOWN_AXIS`]); a rotation only on
    /// a geometry axis, a scale not 0, every component finite
    /// ([`codes::run::FRAME`]).
    pub fn from_value(axes: &FrameAxes, value: &FrameValue) -> Result<Frame, RunError> {
        let mut f = Frame::neutral(axes);
        let mut angles = [0.0; 3];
        for fa in &value.axes {
            let neutral = fa.translation == 0.0
                && fa.fine == 0.0
                && fa.rotation == 0.0
                && fa.scale == 1.0
                && !fa.mirror;
            let Some(i) = axes.index_of(&fa.axis) else {
                if neutral {
                    continue;
                }
                return Err(RunError::new(
                    codes::run::UNKNOWN_AXIS,
                    format!("the frame names `{}`, not an axis of the channel", fa.axis),
                ));
            };
            for (what, v) in [
                ("TR", fa.translation),
                ("FI", fa.fine),
                ("RT", fa.rotation),
                ("SC", fa.scale),
            ] {
                if !v.is_finite() {
                    return Err(RunError::new(
                        codes::run::FRAME,
                        format!(
                            "the frame's `{},{what}` is {v}, not a finite number",
                            fa.axis
                        ),
                    ));
                }
            }
            if fa.scale == 0.0 {
                return Err(scale_zero("the frame's", &fa.axis));
            }
            f.axes[i] = AxisPart {
                coarse: fa.translation,
                fine: fa.fine,
                scale: fa.scale,
                mirror: fa.mirror,
            };
            if fa.rotation != 0.0 {
                match axes.geometry_slot(i) {
                    Some(s) => angles[s] = fa.rotation,
                    None => return Err(not_geometry("the frame's `RT`", &fa.axis)),
                }
            }
        }
        f.rotation = Rotation::from_angles(angles);
        f.check("FRAME")?;
        Ok(f)
    }

    /// The checks every frame passes: finite components, no scale 0, no
    /// rotation that moves a geometry axis the machine does not have.
    fn check(&self, what: &str) -> Result<(), RunError> {
        for a in &self.axes {
            let finite = a.coarse.is_finite() && a.fine.is_finite() && a.scale.is_finite();
            if !finite {
                return Err(RunError::new(
                    codes::run::FRAME,
                    format!("`{what}`: the frame's components exceed the range of a REAL"),
                ));
            }
            if a.scale == 0.0 {
                return Err(RunError::new(
                    codes::run::FRAME,
                    format!("`{what}`: the resulting scale is 0"),
                ));
            }
        }
        let m = &self.rotation.m;
        if !m.iter().flatten().all(|x| x.is_finite()) {
            return Err(RunError::new(
                codes::run::FRAME,
                format!("`{what}`: the rotation is not finite"),
            ));
        }
        // A missing geometry axis may only stay where it is (or turn
        // half-way round onto itself).
        for missing in (0..3).filter(|&s| self.slots[s].is_none()) {
            for other in (0..3).filter(|&s| s != missing) {
                if m[missing][other].abs() > 1e-12 || m[other][missing].abs() > 1e-12 {
                    return Err(RunError::new(
                        codes::run::FRAME,
                        format!(
                            "`{what}`: the rotation would move the geometry axis {} the machine does not have",
                            SLOT_NAMES[missing]
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}

fn check_values(axes: &FrameAxes, keyword: &str, values: &[(usize, f64)]) -> Result<(), RunError> {
    for &(i, v) in values {
        let Some(name) = axes.name(i) else {
            return Err(RunError::new(
                codes::run::UNKNOWN_AXIS,
                format!("`{keyword}`: axis index {i} is not a channel axis"),
            ));
        };
        if !v.is_finite() {
            return Err(RunError::new(
                codes::run::FRAME,
                format!("`{keyword} {name}={v}`: the value is not a finite number"),
            ));
        }
    }
    Ok(())
}

/// The frame of `ROT`/`CROT` values or `RPL=`.
fn rotation_frame(
    axes: &FrameAxes,
    keyword: &str,
    values: &[(usize, f64)],
    rpl: Option<f64>,
    plane: Plane,
) -> Result<Frame, RunError> {
    let mut angles = [0.0; 3];
    for &(i, v) in values {
        let name = axes.name(i).unwrap_or("?");
        match axes.geometry_slot(i) {
            Some(s) => angles[s] = v,
            None => return Err(not_geometry(&format!("`{keyword} {name}`"), name)),
        }
    }
    if let Some(r) = rpl {
        if !values.is_empty() {
            return Err(RunError::new(
                codes::run::FRAME,
                format!("`{keyword}`: `RPL=` and axis angles cannot be combined"),
            ));
        }
        // The plane's infeed is the axis of the rotation.
        angles[plane.infeed()] = r;
    }
    let mut f = Frame::neutral(axes);
    f.rotation = Rotation::from_angles(angles);
    Ok(f)
}

fn scale_frame(
    axes: &FrameAxes,
    keyword: &str,
    values: &[(usize, f64)],
) -> Result<Frame, RunError> {
    let mut f = Frame::neutral(axes);
    for &(i, v) in values {
        if v == 0.0 {
            let name = axes.name(i).unwrap_or("?");
            return Err(scale_zero(&format!("`{keyword}`"), name));
        }
        f.axes[i].scale = v;
    }
    Ok(f)
}

fn not_geometry(what: &str, axis: &str) -> RunError {
    RunError::new(
        codes::run::FRAME,
        format!("{what}: {axis} is not a geometry axis; only the geometry axes rotate"),
    )
}

fn scale_zero(what: &str, axis: &str) -> RunError {
    RunError::new(
        codes::run::FRAME,
        format!("{what} scale of {axis} is 0: a scale factor must not be 0"),
    )
}

// ---------------------------------------------------------------------
// Frame values and functions

/// The frame functions of §9.3 on values: `CTRANS(axis, value, …)` (coarse
/// translation), `CFINE(axis, value, …)` (fine translation), `CROT(axis,
/// angle, …)` (RPY, geometry axes), `CSCALE(axis, factor, …)`,
/// `CMIRROR(axis, …)` and `INVFRAME(frame)`; with no arguments the first
/// five give the neutral frame. `None`: `function` is none of these
/// (`CRPL`, `CROTS` and `MEAFRAME` are not simulated).
pub fn frame_function(
    axes: &FrameAxes,
    function: Function,
    args: &[Option<RtValue>],
) -> Option<Result<RtValue, RunError>> {
    let name = function.name();
    let frame = match function {
        Function::Ctrans | Function::Cfine | Function::Crot | Function::Cscale => {
            pairs(axes, name, args).and_then(|values| match function {
                Function::Ctrans => Frame::translation(axes, &values),
                Function::Cfine => {
                    let mut f = Frame::translation(axes, &values)?;
                    for a in &mut f.axes {
                        a.fine = a.coarse;
                        a.coarse = 0.0;
                    }
                    Ok(f)
                }
                Function::Crot => {
                    check_values(axes, name, &values)?;
                    // Checked with every frame function's result below.
                    rotation_frame(axes, name, &values, None, Plane::G17)
                }
                _ => {
                    check_values(axes, name, &values)?;
                    scale_frame(axes, name, &values)
                }
            })
        }
        Function::Cmirror => (0..args.len())
            .map(|k| axis_arg(axes, name, args, k))
            .collect::<Result<Vec<usize>, RunError>>()
            .map(|indices| {
                let mut f = Frame::neutral(axes);
                for i in indices {
                    f.axes[i].mirror = true;
                }
                f
            }),
        Function::Invframe => match args {
            [Some(RtValue::Frame(v))] => Frame::from_value(axes, v).map(|f| f.inverse()),
            [Some(other)] => Err(RunError::type_mismatch(other, "FRAME")),
            _ => Err(RunError::new(
                codes::run::ARGUMENT_COUNT,
                "`INVFRAME` takes one frame",
            )),
        },
        _ => return None,
    };
    Some(frame.and_then(|f| {
        f.check(name)?;
        Ok(RtValue::Frame(Arc::new(f.to_value(axes))))
    }))
}

/// `(axis, value)` pairs of a frame function.
fn pairs(
    axes: &FrameAxes,
    name: &str,
    args: &[Option<RtValue>],
) -> Result<Vec<(usize, f64)>, RunError> {
    if !args.len().is_multiple_of(2) {
        return Err(RunError::new(
            codes::run::ARGUMENT_COUNT,
            format!(
                "`{name}` takes pairs of an axis and a value, not {} arguments",
                args.len()
            ),
        ));
    }
    let mut values = Vec::with_capacity(args.len() / 2);
    for k in (0..args.len()).step_by(2) {
        let axis = axis_arg(axes, name, args, k)?;
        let value = match &args[k + 1] {
            Some(v) => v.to_real()?,
            None => return Err(omitted(name, k + 1)),
        };
        values.push((axis, value));
    }
    Ok(values)
}

fn axis_arg(
    axes: &FrameAxes,
    name: &str,
    args: &[Option<RtValue>],
    k: usize,
) -> Result<usize, RunError> {
    match args.get(k) {
        Some(Some(RtValue::Axis(a))) => axes.index_of(a).ok_or_else(|| {
            RunError::new(
                codes::run::UNKNOWN_AXIS,
                format!("`{name}`: `{a}` is not an axis of the channel"),
            )
        }),
        Some(Some(other)) => Err(RunError::new(
            codes::run::TYPE_MISMATCH,
            format!(
                "`{name}`: argument {} must be an axis, not a {} value",
                k + 1,
                other.type_name()
            ),
        )),
        _ => Err(omitted(name, k)),
    }
}

fn omitted(name: &str, k: usize) -> RunError {
    RunError::new(
        codes::run::ARGUMENT_COUNT,
        format!("`{name}`: argument {} is omitted", k + 1),
    )
}

/// The `:` operator on FRAME values: `lhs : rhs`, `rhs` acting inside
/// `lhs` ([`Frame::chain`]).
pub fn chain_values(
    axes: &FrameAxes,
    lhs: &FrameValue,
    rhs: &FrameValue,
) -> Result<FrameValue, RunError> {
    let f = Frame::from_value(axes, lhs)?.chain(&Frame::from_value(axes, rhs)?);
    f.check(":")?;
    Ok(f.to_value(axes))
}

// ---------------------------------------------------------------------
// Numbers

/// Sine and cosine of an angle in degrees; exact at multiples of 90°.
fn sin_cos_deg(d: f64) -> (f64, f64) {
    let r = d.rem_euclid(360.0);
    if r == 0.0 {
        (0.0, 1.0)
    } else if r == 90.0 {
        (1.0, 0.0)
    } else if r == 180.0 {
        (0.0, -1.0)
    } else if r == 270.0 {
        (-1.0, 0.0)
    } else {
        r.to_radians().sin_cos()
    }
}

/// The rotation about slot `s` (0 X, 1 Y, 2 Z) by `d` degrees,
/// right-handed (counter-clockwise looking from the positive axis).
fn axis_rotation(s: usize, d: f64) -> Mat3 {
    if d == 0.0 {
        return IDENTITY;
    }
    let (sn, c) = sin_cos_deg(d);
    match s {
        0 => [[1.0, 0.0, 0.0], [0.0, c, -sn], [0.0, sn, c]],
        1 => [[c, 0.0, sn], [0.0, 1.0, 0.0], [-sn, 0.0, c]],
        _ => [[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]],
    }
}

fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    let mut m = [[0.0; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    m
}

fn mul_vec(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

fn transpose(m: &Mat3) -> Mat3 {
    [
        [m[0][0], m[1][0], m[2][0]],
        [m[0][1], m[1][1], m[2][1]],
        [m[0][2], m[1][2], m[2][2]],
    ]
}

/// An angle within 1e-9° of a whole degree as that degree; −0 and −180
/// as 0 and 180.
fn snap_degrees(a: f64) -> f64 {
    let r = a.round();
    let a = if (a - r).abs() < 1e-9 { r } else { a };
    if a == -180.0 { 180.0 } else { a + 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) {
        assert!((a - b).abs() < 1e-12, "got {a}, expected {b}");
    }

    /// A clone is the same frame at once; frames made apart are the same
    /// when their contents are, and a changed frame is another.
    #[test]
    fn frames_are_the_same_by_id_or_by_contents() {
        let axes = FrameAxes::new([("X", true), ("Y", true), ("Z", true)]);
        let plane = Plane::G17;
        let mut shifted = Frame::neutral(&axes);
        shifted
            .apply(&axes, FrameOp::Trans, &[(0, 5.0)], None, plane)
            .unwrap();
        let clone = shifted.clone();
        assert!(clone.same_as(&shifted) && clone.id == shifted.id);
        let mut again = Frame::neutral(&axes);
        again
            .apply(&axes, FrameOp::Trans, &[(0, 5.0)], None, plane)
            .unwrap();
        assert!(again.id != shifted.id && again.same_as(&shifted));
        let mut moved = clone.clone();
        moved
            .apply(&axes, FrameOp::Atrans, &[(1, 1.0)], None, plane)
            .unwrap();
        assert!(!moved.same_as(&clone) && moved.id != clone.id);
        assert!(!Frame::neutral(&axes).same_as(&shifted));
    }

    /// Frames whose axes are exactly neutral take the short way into the
    /// frame, frames that only translate (identity frames too) the short
    /// way out: they give the general paths' bits, zeros' signs included,
    /// with and without a rotation (one of zero angles too), on a machine
    /// with an axis past the frame's, for infinite and NaN coordinates
    /// too. Frames that translate by `-0.0`, rotate, scale or mirror take
    /// the general way out.
    #[test]
    fn the_neutral_and_translation_paths_give_the_general_paths_bits() {
        let axes = FrameAxes::new([("X", true), ("Y", true), ("Z", true), ("A", false)]);
        let plane = Plane::G17;
        let framed = |op: FrameOp, values: &[(usize, f64)]| {
            let mut frame = Frame::neutral(&axes);
            frame.apply(&axes, op, values, None, plane).unwrap();
            frame
        };
        let mut rotated = framed(FrameOp::Rot, &[(2, 90.0)]);
        rotated.rotation = Rotation::from_angles([0.0, 0.0, 0.0]);
        let neutral = [
            Frame::neutral(&axes),
            framed(FrameOp::Rot, &[(2, 30.0)]),
            rotated,
            framed(FrameOp::Trans, &[(0, 0.0)]),
        ];
        let mut translated_and_rotated = framed(FrameOp::Trans, &[(0, 3.0), (2, -1.5)]);
        translated_and_rotated.rotation = framed(FrameOp::Rot, &[(2, 30.0)]).rotation;
        let mut translated_by_identity = framed(FrameOp::Trans, &[(0, 3.0), (1, 0.0)]);
        translated_by_identity.rotation = Rotation::from_angles([0.0, 0.0, 0.0]);
        // Coarse and fine both `-0.0`: a translation of `-0.0`.
        let mut minus_zero = framed(FrameOp::Trans, &[(0, -0.0), (1, 2.0)]);
        minus_zero.axes[0].fine = -0.0;
        let not_neutral = [
            framed(FrameOp::Trans, &[(0, -0.0)]),
            framed(FrameOp::Trans, &[(1, 5.0), (3, -2.0)]),
            // A work offset: every axis translated, one by `+0.0`.
            framed(
                FrameOp::Trans,
                &[(0, -412.5), (1, -220.0), (2, 0.0), (3, 515.3)],
            ),
            framed(FrameOp::Trans, &[(0, -0.0), (1, 2.0)]),
            translated_and_rotated,
            translated_by_identity,
            minus_zero,
            framed(FrameOp::Scale, &[(0, 2.0)]),
            framed(FrameOp::Mirror, &[(1, 0.0)]),
        ];
        for frame in &neutral {
            assert!(frame.axes_exactly_neutral(), "{frame:?}");
        }
        assert!(neutral[0].is_identity() && neutral[2].is_identity());
        assert!(!neutral[1].is_identity());
        for frame in &not_neutral {
            assert!(!frame.axes_exactly_neutral(), "{frame:?}");
        }
        let values = [
            0.0,
            -0.0,
            1.5,
            -2.25,
            1e-300,
            f64::MAX,
            -7.0,
            f64::INFINITY,
            f64::NAN,
        ];
        for frame in neutral.iter().chain(&not_neutral) {
            for x in values {
                for y in values {
                    for (z, a) in [(0.0, -0.0), (-0.0, 3.0), (-1.0, -0.0)] {
                        let point = [x, y, z, a, -0.0];
                        for len in [5, 4, 2] {
                            let (mut fast, mut general) = ([9.0; 5], [9.0; 5]);
                            let n = frame.axes.len().min(len);
                            frame.to_outer(&point[..len], &mut fast);
                            frame.general_to_outer(&point[..len], &mut general, len, n);
                            assert_eq!(fast.map(f64::to_bits), general.map(f64::to_bits));
                            frame.to_inner(&point[..len], &mut fast);
                            frame.general_to_inner(&point[..len], &mut general, len, n);
                            assert_eq!(fast.map(f64::to_bits), general.map(f64::to_bits));
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn sin_cos_exact_at_right_angles() {
        assert_eq!(sin_cos_deg(90.0), (1.0, 0.0));
        assert_eq!(sin_cos_deg(-90.0), (-1.0, 0.0));
        assert_eq!(sin_cos_deg(540.0), (0.0, -1.0));
        let (s, c) = sin_cos_deg(30.0);
        close(s, 0.5);
        close(c, 3f64.sqrt() / 2.0);
    }

    #[test]
    fn decomposition_recovers_rpy_angles() {
        for angles in [
            [10.0, 20.0, 30.0],
            [-170.0, 89.0, 179.0],
            [0.0, 0.0, -45.0],
            [33.3, -12.5, 100.0],
        ] {
            let r = Rotation::from_matrix(&Rotation::from_angles(angles).m);
            for k in 0..3 {
                assert!((r.angles[k] - angles[k]).abs() < 1e-9, "{angles:?}: {r:?}");
            }
        }
        // Gimbal lock: y = 90 folds x into z: Rz(c)·Ry(90)·Rx(a) depends
        // on c − a only, so (10, 90, 30) reads (0, 90, 20).
        let r = Rotation::from_matrix(&Rotation::from_angles([10.0, 90.0, 30.0]).m);
        assert_eq!(r.angles, [0.0, 90.0, 20.0]);
    }

    #[test]
    fn mirrored_rotation_matches_conjugation() {
        let r = Rotation::from_angles([10.0, 20.0, 30.0]);
        let mirror = [true, false, true];
        let d = [-1.0, 1.0, -1.0];
        let got = r.mirrored(mirror).m;
        for i in 0..3 {
            for j in 0..3 {
                close(got[i][j], d[i] * r.m[i][j] * d[j]);
            }
        }
    }

    #[test]
    fn slots_of_a_lathe_and_of_unusual_names() {
        let lathe = FrameAxes::new([("X", true), ("Z", true), ("C", false)]);
        assert_eq!(lathe.geometry_slot(0), Some(0));
        assert_eq!(lathe.geometry_slot(1), Some(2));
        assert_eq!(lathe.geometry_slot(2), None);
        assert_eq!(lathe.geometry_axis(1), None);
        let odd = FrameAxes::new([("Z", true), ("U1", true), ("V1", true), ("W1", true)]);
        assert_eq!(odd.geometry_slot(0), Some(2));
        assert_eq!(odd.geometry_slot(1), Some(0));
        assert_eq!(odd.geometry_slot(2), Some(1));
        // A fourth geometry axis is a special axis.
        assert_eq!(odd.geometry_slot(3), None);
    }
}
