//! The few functions and types of Intel Embree 3 (3.13) this program uses,
//! declared by hand from `embree3/rtcore_*.h`, and a safe owner of a device
//! and of a scene with one user geometry.
//!
//! Layouts follow the headers of the build with `RTC_MAX_INSTANCE_LEVEL_COUNT
//! 1` and `RTC_MIN_WIDTH 0` (Debian's `libembree-dev` 3.13.5).

use std::ffi::{CString, c_char, c_int, c_uint, c_void};

/// `RTC_INVALID_GEOMETRY_ID`.
pub const INVALID_ID: u32 = u32::MAX;

/// `RTC_GEOMETRY_TYPE_USER`.
const GEOMETRY_TYPE_USER: c_uint = 120;

/// `RTCBuildQuality`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C)]
pub enum BuildQuality {
    /// `RTC_BUILD_QUALITY_LOW`.
    Low = 0,
    /// `RTC_BUILD_QUALITY_MEDIUM` (Embree's default).
    Medium = 1,
    /// `RTC_BUILD_QUALITY_HIGH`.
    High = 2,
}

/// `struct RTCRay`: one ray, f32.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(16))]
pub struct RtcRay {
    pub org: [f32; 3],
    pub tnear: f32,
    pub dir: [f32; 3],
    pub time: f32,
    pub tfar: f32,
    pub mask: u32,
    pub id: u32,
    pub flags: u32,
}

/// `struct RTCHit`.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(16))]
pub struct RtcHit {
    pub ng: [f32; 3],
    pub u: f32,
    pub v: f32,
    pub prim_id: u32,
    pub geom_id: u32,
    pub inst_id: [u32; 1],
}

/// `struct RTCRayHit`.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C)]
pub struct RtcRayHit {
    pub ray: RtcRay,
    pub hit: RtcHit,
}

/// `struct RTCRay16`: sixteen rays, one array per field.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct RtcRay16 {
    pub org_x: [f32; 16],
    pub org_y: [f32; 16],
    pub org_z: [f32; 16],
    pub tnear: [f32; 16],
    pub dir_x: [f32; 16],
    pub dir_y: [f32; 16],
    pub dir_z: [f32; 16],
    pub time: [f32; 16],
    pub tfar: [f32; 16],
    pub mask: [u32; 16],
    pub id: [u32; 16],
    pub flags: [u32; 16],
}

/// `struct RTCHit16`.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub struct RtcHit16 {
    pub ng_x: [f32; 16],
    pub ng_y: [f32; 16],
    pub ng_z: [f32; 16],
    pub u: [f32; 16],
    pub v: [f32; 16],
    pub prim_id: [u32; 16],
    pub geom_id: [u32; 16],
    pub inst_id: [[u32; 16]; 1],
}

/// `struct RTCRayHit16`.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub struct RtcRayHit16 {
    pub ray: RtcRay16,
    pub hit: RtcHit16,
}

/// The `valid` mask of a packet of 16 rays: -1 for a ray to trace, 0 for
/// none; Embree reads it with aligned vector loads (64 bytes).
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(64))]
pub struct Valid16(pub [c_int; 16]);

/// `struct RTCIntersectContext` (without `instStackSize` and
/// `minWidthDistanceFactor`, absent from this build).
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub struct RtcIntersectContext {
    /// `RTCIntersectContextFlags`: 0 incoherent, 1 coherent.
    pub flags: c_uint,
    /// The filter function: none.
    pub filter: Option<unsafe extern "C" fn(*const c_void)>,
    pub inst_id: [u32; 1],
}

impl RtcIntersectContext {
    /// What `rtcInitIntersectContext` sets (an inline function of the
    /// header), with `coherent` rays or not.
    pub fn new(coherent: bool) -> RtcIntersectContext {
        RtcIntersectContext { flags: c_uint::from(coherent), filter: None, inst_id: [INVALID_ID] }
    }
}

/// `struct RTCBounds`.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(16))]
pub struct RtcBounds {
    pub lower: [f32; 3],
    pub align0: f32,
    pub upper: [f32; 3],
    pub align1: f32,
}

/// `struct RTCBoundsFunctionArguments`.
#[repr(C)]
pub struct BoundsArguments {
    pub user: *mut c_void,
    pub prim_id: c_uint,
    pub time_step: c_uint,
    pub bounds: *mut RtcBounds,
}

/// `struct RTCIntersectFunctionNArguments`; `rayhit` points to N rays and
/// hits, laid out as [`RtcRayHit`] for N = 1 and [`RtcRayHit16`] for N = 16
/// (each field an array of N).
#[repr(C)]
pub struct IntersectArguments {
    pub valid: *mut c_int,
    pub user: *mut c_void,
    pub prim_id: c_uint,
    pub context: *mut RtcIntersectContext,
    pub rayhit: *mut f32,
    pub n: c_uint,
    pub geom_id: c_uint,
}

/// `struct RTCOccludedFunctionNArguments`; `ray` points to N rays, laid
/// out as for [`IntersectArguments`].
#[repr(C)]
pub struct OccludedArguments {
    pub valid: *mut c_int,
    pub user: *mut c_void,
    pub prim_id: c_uint,
    pub context: *mut RtcIntersectContext,
    pub ray: *mut f32,
    pub n: c_uint,
    pub geom_id: c_uint,
}

/// Index, in f32 words, of field `field` (0 `org_x` .. 11 `flags`) of ray
/// `lane` in a block of `n` rays laid out as `RTCRayN`.
#[inline(always)]
pub fn ray_field(field: usize, n: usize, lane: usize) -> usize {
    field * n + lane
}

/// Field numbers of `RTCRayN` and `RTCHitN` (the hit follows the 12 ray fields).
pub const TFAR: usize = 8;
pub const ID: usize = 10;
pub const PRIM_ID: usize = 12 + 5;
pub const GEOM_ID: usize = 12 + 6;

type Device = *mut c_void;
type Scene = *mut c_void;
type Geometry = *mut c_void;

#[link(name = "embree3")]
unsafe extern "C" {
    fn rtcNewDevice(config: *const c_char) -> Device;
    fn rtcReleaseDevice(device: Device);
    fn rtcGetDeviceError(device: Device) -> c_int;
    fn rtcNewScene(device: Device) -> Scene;
    fn rtcReleaseScene(scene: Scene);
    fn rtcSetSceneBuildQuality(scene: Scene, quality: BuildQuality);
    fn rtcCommitScene(scene: Scene);
    fn rtcNewGeometry(device: Device, kind: c_uint) -> Geometry;
    fn rtcReleaseGeometry(geometry: Geometry);
    fn rtcCommitGeometry(geometry: Geometry);
    fn rtcAttachGeometry(scene: Scene, geometry: Geometry) -> c_uint;
    fn rtcSetGeometryBuildQuality(geometry: Geometry, quality: BuildQuality);
    fn rtcSetGeometryUserPrimitiveCount(geometry: Geometry, count: c_uint);
    fn rtcSetGeometryUserData(geometry: Geometry, user: *mut c_void);
    fn rtcSetGeometryBoundsFunction(
        geometry: Geometry,
        bounds: unsafe extern "C" fn(*const BoundsArguments),
        user: *mut c_void,
    );
    fn rtcSetGeometryIntersectFunction(geometry: Geometry, intersect: unsafe extern "C" fn(*const IntersectArguments));
    fn rtcSetGeometryOccludedFunction(geometry: Geometry, occluded: unsafe extern "C" fn(*const OccludedArguments));
    fn rtcIntersect1(scene: Scene, context: *mut RtcIntersectContext, rayhit: *mut RtcRayHit);
    fn rtcOccluded1(scene: Scene, context: *mut RtcIntersectContext, ray: *mut RtcRay);
    fn rtcIntersect16(valid: *const Valid16, scene: Scene, context: *mut RtcIntersectContext, rayhit: *mut RtcRayHit16);
    fn rtcOccluded16(valid: *const Valid16, scene: Scene, context: *mut RtcIntersectContext, ray: *mut RtcRay16);
}

/// An Embree device (its thread pool and its chosen ISA).
pub struct EmbreeDevice(Device);

impl EmbreeDevice {
    /// A device made with the configuration string `config` (e.g.
    /// `"threads=2,verbose=1"`).
    pub fn new(config: &str) -> Result<EmbreeDevice, String> {
        let config = CString::new(config).map_err(|_| "a NUL in the Embree configuration".to_owned())?;
        // SAFETY: `config` is a NUL-terminated string that outlives the call.
        let device = unsafe { rtcNewDevice(config.as_ptr()) };
        if device.is_null() {
            // SAFETY: a null device asks for the error of the last device creation.
            let error = unsafe { rtcGetDeviceError(std::ptr::null_mut()) };
            return Err(format!("rtcNewDevice failed (RTCError {error})"));
        }
        Ok(EmbreeDevice(device))
    }

    /// The last error on this device (0 for none).
    fn error(&self) -> c_int {
        // SAFETY: `self.0` is a live device.
        unsafe { rtcGetDeviceError(self.0) }
    }
}

impl Drop for EmbreeDevice {
    fn drop(&mut self) {
        // SAFETY: `self.0` is a live device; scenes hold their own reference.
        unsafe { rtcReleaseDevice(self.0) }
    }
}

/// The callbacks of a user geometry; each receives the scene's user data
/// as `user` (`geometryUserPtr`).
pub struct UserCallbacks {
    pub bounds: unsafe extern "C" fn(*const BoundsArguments),
    pub intersect: unsafe extern "C" fn(*const IntersectArguments),
    pub occluded: unsafe extern "C" fn(*const OccludedArguments),
}

/// A committed Embree scene of one user geometry of `count` primitives
/// whose callbacks read `data`; it borrows `data` for its whole life.
pub struct EmbreeScene<'a, T: Sync> {
    scene: Scene,
    _data: std::marker::PhantomData<&'a T>,
}

// SAFETY: a committed Embree scene may be traced from any number of
// threads at once (Embree's documented contract for rtcIntersect* and
// rtcOccluded*), and the user data it reads is `Sync` and only read.
unsafe impl<T: Sync> Sync for EmbreeScene<'_, T> {}

impl<'a, T: Sync> EmbreeScene<'a, T> {
    /// Builds (commits) the scene: `count` primitives of one user geometry
    /// with `callbacks` over `data`, with build quality `quality`. An empty
    /// scene (count 0) has no geometry.
    pub fn build(
        device: &EmbreeDevice,
        data: &'a T,
        count: u32,
        callbacks: &UserCallbacks,
        quality: BuildQuality,
    ) -> Result<EmbreeScene<'a, T>, String> {
        let user = data as *const T as *mut c_void;
        // SAFETY: `device.0` is live; every handle made here is checked
        // against null or through the device error; the callbacks only read
        // `data`, which outlives the scene ('a), through `user`.
        unsafe {
            let scene = rtcNewScene(device.0);
            if scene.is_null() {
                return Err(format!("rtcNewScene failed (RTCError {})", device.error()));
            }
            rtcSetSceneBuildQuality(scene, quality);
            if count > 0 {
                let geometry = rtcNewGeometry(device.0, GEOMETRY_TYPE_USER);
                if geometry.is_null() {
                    rtcReleaseScene(scene);
                    return Err(format!("rtcNewGeometry failed (RTCError {})", device.error()));
                }
                rtcSetGeometryBuildQuality(geometry, quality);
                rtcSetGeometryUserPrimitiveCount(geometry, count);
                rtcSetGeometryUserData(geometry, user);
                rtcSetGeometryBoundsFunction(geometry, callbacks.bounds, user);
                rtcSetGeometryIntersectFunction(geometry, callbacks.intersect);
                rtcSetGeometryOccludedFunction(geometry, callbacks.occluded);
                rtcCommitGeometry(geometry);
                rtcAttachGeometry(scene, geometry);
                // The scene keeps its own reference.
                rtcReleaseGeometry(geometry);
            }
            rtcCommitScene(scene);
            let error = device.error();
            if error != 0 {
                rtcReleaseScene(scene);
                return Err(format!("Embree failed to build the scene (RTCError {error})"));
            }
            Ok(EmbreeScene { scene, _data: std::marker::PhantomData })
        }
    }

    /// `rtcIntersect1`: the callbacks see `context` (which may be the first
    /// field of a larger `#[repr(C)]` struct they know) and `rayhit`.
    #[inline]
    pub fn intersect1(&self, context: &mut RtcIntersectContext, rayhit: &mut RtcRayHit) {
        // SAFETY: the scene is committed and alive; both pointers are valid
        // and exclusive for the call.
        unsafe { rtcIntersect1(self.scene, context, rayhit) }
    }

    /// `rtcOccluded1`: `ray.tfar` becomes `-inf` when something is hit.
    #[inline]
    pub fn occluded1(&self, context: &mut RtcIntersectContext, ray: &mut RtcRay) {
        // SAFETY: as for `intersect1`.
        unsafe { rtcOccluded1(self.scene, context, ray) }
    }

    /// `rtcIntersect16` over the lanes whose `valid` is -1.
    #[inline]
    pub fn intersect16(&self, valid: &Valid16, context: &mut RtcIntersectContext, rayhit: &mut RtcRayHit16) {
        // SAFETY: as for `intersect1`; `valid` and the packet have Embree's
        // 64-byte alignment (their types').
        unsafe { rtcIntersect16(valid, self.scene, context, rayhit) }
    }

    /// `rtcOccluded16` over the lanes whose `valid` is -1.
    #[inline]
    pub fn occluded16(&self, valid: &Valid16, context: &mut RtcIntersectContext, ray: &mut RtcRay16) {
        // SAFETY: as for `intersect16`.
        unsafe { rtcOccluded16(valid, self.scene, context, ray) }
    }
}

impl<T: Sync> Drop for EmbreeScene<'_, T> {
    fn drop(&mut self) {
        // SAFETY: `self.scene` is a live scene, released once.
        unsafe { rtcReleaseScene(self.scene) }
    }
}
