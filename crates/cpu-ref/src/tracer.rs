//! Ray casting against the scene's triangles with an obvhs compressed wide BVH. Triangles of
//! alpha-masked materials are cut out where their mask says so, for every query (camera,
//! RSM and shadow rays): a hit there is ignored and the ray goes on (any-hit test).
mod packet;

pub use packet::Rays8;

use crate::watertight::{barycentric, ShearedRay};
use glam::{Vec2, Vec3, Vec3A};
use obvhs::cwbvh::{builder::build_cwbvh_from_tris, CwBvh};
use obvhs::ray::{Ray, RayHit};
use obvhs::triangle::Triangle;
use obvhs::BvhBuildParams;
use slc_bounds::Brdf;
use slc_core::texture::Texture;
use slc_core::{AlphaMask, Scene};
use std::time::Duration;

/// Which mesh triangle a BVH primitive is.
#[derive(Clone, Copy, Debug)]
struct PrimRef {
    mesh: u32,
    tri: u32,
    /// Index into `Tracer::cutouts`, [`NOT_MASKED`] for opaque triangles.
    cutout: u32,
}

const NOT_MASKED: u32 = u32::MAX;

/// What the any-hit test of an alpha-masked triangle needs.
#[derive(Clone, Copy, Debug)]
struct Cutout {
    /// The texture coordinates of its vertices (`None`: the mask's factor alone counts).
    uvs: Option<[Vec2; 3]>,
    mask: AlphaMask,
}

/// A BVH over every triangle of a scene, with closest-hit and occlusion queries.
pub struct Tracer {
    bvh: CwBvh,
    /// Triangles in BVH primitive order.
    tris: Vec<Triangle>,
    prims: Vec<PrimRef>,
    cutouts: Vec<Cutout>,
    /// The textures of the masks of `cutouts` (their own copies, indexed by the masks).
    textures: Vec<Texture>,
    /// Offset that lifts ray origins off surfaces, relative to the scene's size.
    epsilon: f32,
}

/// A ray-surface intersection, oriented for shading.
#[derive(Clone, Copy, Debug)]
pub struct SurfaceHit {
    pub position: Vec3,
    /// Unit geometric normal, facing the incoming ray for two-sided materials, as authored otherwise.
    pub geometric_normal: Vec3,
    /// Unit shading normal on the same side as `geometric_normal`.
    pub shading_normal: Vec3,
    /// Whether a normal map perturbed the shading normal (VPLs left there take the adjoint
    /// correction of `slc_bounds::shading_normal`).
    pub normal_mapped: bool,
    /// Whether the ray hit the side the (oriented) geometric normal points to. A one-sided
    /// surface seen from behind is black and reflects nothing.
    pub front: bool,
    pub brdf: Brdf,
    pub distance: f32,
}

impl Tracer {
    pub fn new(scene: &Scene) -> Self {
        let mut tris = Vec::with_capacity(scene.triangle_count());
        let mut prims = Vec::with_capacity(scene.triangle_count());
        let mut cutouts = Vec::new();
        // The masks' textures only, each once; the masks refer to them by their new index.
        let mut textures: Vec<Texture> = Vec::new();
        let mut copied = std::collections::HashMap::new();
        for (mi, mesh) in scene.meshes.iter().enumerate() {
            let mask = scene.materials[mesh.material].alpha_mask.map(|mut m| {
                m.texture = m.texture.and_then(|id| {
                    let texture = scene.textures.get(id)?;
                    Some(*copied.entry(id).or_insert_with(|| {
                        textures.push(texture.clone());
                        textures.len() - 1
                    }))
                });
                m
            });
            for (ti, t) in mesh.triangles.iter().enumerate() {
                let [v0, v1, v2] = t.map(|i| Vec3A::from(mesh.positions[i as usize]));
                tris.push(Triangle { v0, v1, v2 });
                let cutout = match mask {
                    Some(mask) => {
                        let uvs = mesh.uvs.as_ref().map(|uv| t.map(|i| uv[i as usize]));
                        cutouts.push(Cutout { uvs, mask });
                        cutouts.len() as u32 - 1
                    }
                    None => NOT_MASKED,
                };
                prims.push(PrimRef {
                    mesh: mi as u32,
                    tri: ti as u32,
                    cutout,
                });
            }
        }
        let bvh = build_cwbvh_from_tris(
            &tris,
            BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let order = &bvh.primitive_indices;
        let tris = order.iter().map(|&i| tris[i as usize]).collect();
        let prims = order.iter().map(|&i| prims[i as usize]).collect();
        Self {
            bvh,
            tris,
            prims,
            cutouts,
            textures,
            epsilon: scene.ray_epsilon(),
        }
    }

    /// The ray's distance to BVH primitive `id` within (tmin, tmax], infinite where it misses
    /// or meets the triangle where its mask cuts it away (at the hit's own barycentrics).
    #[inline]
    fn hit_distance(&self, ray: &ShearedRay, id: usize, tmin: f32, tmax: f32) -> f32 {
        let tri = &self.tris[id];
        let cutout = self.prims[id].cutout;
        if cutout == NOT_MASKED {
            return ray.intersect(tri, tmin, tmax);
        }
        let Some((t, [w0, w1, w2])) = ray.hit(tri, tmin, tmax) else {
            return f32::INFINITY;
        };
        let c = &self.cutouts[cutout as usize];
        let uv = c.uvs.map(|[a, b, cc]| a * w0 + b * w1 + cc * w2);
        if c.mask.cuts(uv, &self.textures) {
            f32::INFINITY
        } else {
            t
        }
    }

    /// The origin offset used to leave a surface ([`Scene::ray_epsilon`]).
    pub fn epsilon(&self) -> f32 {
        self.epsilon
    }

    /// Closest hit along `origin + t dir`, t in (0, tmax).
    pub fn intersect(
        &self,
        scene: &Scene,
        origin: Vec3,
        dir: Vec3,
        tmax: f32,
    ) -> Option<SurfaceHit> {
        let (t, prim) = self.closest(origin, dir, 0.0, tmax)?;
        Some(self.surface_at(scene, prim, origin, dir, t))
    }

    /// The closest hits of up to eight rays from `origin` along `rays.dir`, t in (0,
    /// `rays.tmax`) (`rays.origin` and `rays.tmin` are ignored): each what
    /// [`Tracer::intersect`] finds for the ray alone, traced together where the rays are
    /// coherent ([`Rays8`]).
    pub fn intersect8(&self, scene: &Scene, origin: Vec3, rays: &Rays8) -> [Option<SurfaceHit>; 8] {
        self.intersect_rays8(
            scene,
            &Rays8 {
                origin: [origin; 8],
                tmin: [0.0; 8],
                ..*rays
            },
        )
    }

    /// The closest hits of up to eight rays within (tmin, tmax) (`None` for lanes not in
    /// use): each ray's [`Tracer::closest`] and the surface there (for `tmin` 0 what
    /// [`Tracer::intersect`] finds), traced together where the rays are coherent ([`Rays8`]).
    pub fn intersect_rays8(&self, scene: &Scene, rays: &Rays8) -> [Option<SurfaceHit>; 8] {
        let hits = self.closest8(rays);
        std::array::from_fn(|i| {
            let (t, prim) = hits[i]?;
            Some(self.surface_at(scene, prim, rays.origin[i], rays.dir[i], t))
        })
    }

    /// The distance and BVH primitive of the closest hit in (tmin, tmax): the traversal of
    /// [`Tracer::intersect`] without the surface at the hit.
    pub fn closest(&self, origin: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> Option<(f32, u32)> {
        let ray = Ray::new(origin.into(), dir.into(), tmin, tmax);
        let sheared = ShearedRay::new(origin, dir);
        let mut hit = RayHit::none();
        self.bvh
            .ray_traverse(ray, &mut hit, |r, id| {
                self.hit_distance(&sheared, id, r.tmin, r.tmax)
            })
            .then_some((hit.t, hit.primitive_id))
    }

    /// The surface at distance `t` along the ray from `origin` along `dir` on BVH primitive
    /// `prim`.
    fn surface_at(&self, scene: &Scene, prim: u32, origin: Vec3, dir: Vec3, t: f32) -> SurfaceHit {
        self.surface(scene, prim as usize, origin + dir * t, dir, t)
    }

    /// Whether the segment from `from` to `to` is free of geometry (ends excluded by epsilon).
    pub fn unoccluded(&self, from: Vec3, to: Vec3) -> bool {
        match self.segment_ray(from, to) {
            Some((dir, tmin, tmax)) => self.segment_is_free(from, dir, tmin, tmax),
            None => true,
        }
    }

    /// The ray [`Tracer::unoccluded`] traces from `from` to `to`: its unit direction and its
    /// range (tmin, tmax], the ends excluded by epsilon; `None` where the ends lie within two
    /// epsilons (free without a ray).
    pub fn segment_ray(&self, from: Vec3, to: Vec3) -> Option<(Vec3, f32, f32)> {
        let d = to - from;
        let len = d.length();
        (len > 2.0 * self.epsilon).then(|| (d / len, self.epsilon, len - self.epsilon))
    }

    /// The ray [`Tracer::escapes`] traces from `from` along `dir`: its range (tmin, tmax].
    pub fn escape_range(&self) -> (f32, f32) {
        (self.epsilon, f32::INFINITY)
    }

    /// The rays of `rays` in use that meet geometry within their ranges: each ray what
    /// `Tracer::segment_is_free` says for it alone, negated, traced together where the rays
    /// are coherent ([`Rays8`]).
    pub fn occluded8(&self, rays: &Rays8) -> u8 {
        self.blocked8(rays)
    }

    /// Whether the ray from `from` along `dir` escapes the scene (for directional lights).
    pub fn escapes(&self, from: Vec3, dir: Vec3) -> bool {
        let (tmin, tmax) = self.escape_range();
        self.segment_is_free(from, dir, tmin, tmax)
    }

    fn segment_is_free(&self, from: Vec3, dir: Vec3, tmin: f32, tmax: f32) -> bool {
        let ray = Ray::new(from.into(), dir.into(), tmin, tmax);
        let sheared = ShearedRay::new(from, dir);
        self.bvh
            .ray_traverse_miss(ray, |r, id| self.hit_distance(&sheared, id, r.tmin, r.tmax))
    }

    /// A point just off the surface at `p` on the side of `n`.
    #[inline]
    pub fn lift(&self, p: Vec3, n: Vec3) -> Vec3 {
        p + n * self.epsilon
    }

    fn surface(
        &self,
        scene: &Scene,
        prim: usize,
        position: Vec3,
        dir: Vec3,
        distance: f32,
    ) -> SurfaceHit {
        let r = self.prims[prim];
        let mesh = &scene.meshes[r.mesh as usize];
        let material = &scene.materials[mesh.material];
        let idx = mesh.triangles[r.tri as usize].map(|i| i as usize);
        let [a, b, c] = idx.map(|i| mesh.positions[i]);
        let mut ng = (b - a).cross(c - a).normalize();
        let (w0, w1, w2) = barycentric(a, b, c, position);
        let interpolated = mesh
            .normals
            .as_ref()
            .and_then(|n| (n[idx[0]] * w0 + n[idx[1]] * w1 + n[idx[2]] * w2).try_normalize())
            .unwrap_or(ng);
        let uv = mesh
            .uvs
            .as_ref()
            .map(|t| t[idx[0]] * w0 + t[idx[1]] * w1 + t[idx[2]] * w2);
        let tangent = mesh.tangents.as_ref().map(|t| {
            let xyz =
                t[idx[0]].truncate() * w0 + t[idx[1]].truncate() * w1 + t[idx[2]].truncate() * w2;
            xyz.extend(t[idx[0]].w)
        });
        let mapped = material.mapped_normal(interpolated, ng, tangent, uv, &scene.textures);
        let normal_mapped = mapped.is_some();
        let mut ns = mapped.unwrap_or(interpolated);
        let mut front = dir.dot(ng) < 0.0;
        if material.double_sided && !front {
            ng = -ng;
            front = true;
        }
        // A flipped shading normal (the back of a double-sided surface) keeps the tangent
        // frame's bitangent, as glTF viewers flip T and B with it: the anisotropy keeps its
        // line on both sides (Mitsuba's `twosided` mirrors only the normal's axis).
        let mut tangent = tangent;
        if ns.dot(ng) < 0.0 {
            ns = -ns;
            tangent = tangent.map(|t| t.with_w(-t.w));
        }
        let brdf = material.surface_brdf(uv, ns, tangent, &scene.textures);
        SurfaceHit {
            position,
            geometric_normal: ng,
            shading_normal: ns,
            normal_mapped,
            front,
            brdf,
            distance,
        }
    }
}
