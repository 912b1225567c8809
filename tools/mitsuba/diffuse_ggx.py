"""`diffuse_ggx`: the renderer's material model as a Mitsuba 3 Python BSDF plugin.

BRDF (exactly the one documented in ../shared/reference/cornell-a (beside the repository)/README.md):

    f(wi, wo) = kd / pi + F(wi.h) D(h) G1(wi) G1(wo) / (4 cos_i cos_o)

    h  = normalize(wi + wo)
    F  = F0 + (1 - F0) (1 - wi.h)^5                          (Schlick)
    D  = 1 / (pi a^2 (cos^2 th_h + sin^2 th_h / a^2)^2)      (GGX / Trowbridge-Reitz)
       = a^2 / (pi ((a^2 - 1) cos^2 th_h + 1)^2)
    G1 = 2 / (1 + sqrt(1 + a^2 tan^2 th_v))                  (separable Smith, NOT height-correlated)

with a = alpha (the GGX alpha = roughness^2). Anisotropic (glTF KHR_materials_anisotropy, when
`alpha_t` is given): D and G1 are Mitsuba's own anisotropic GGX (mi.MicrofacetDistribution with
alpha_u = alpha_t along the direction cos(rotation) s + sin(rotation) t of the local shading
frame (s = normalized dp/du, t = n x s), alpha_v = alpha across it), with the same separable
Smith G and Schlick F. One-sided: f = 0 unless both directions lie above
the shading normal (cos_i > 0 and cos_o > 0 in Mitsuba's local shading frame). The diffuse term
is NOT weighted by (1 - F). Like every Mitsuba BSDF, eval() returns f * cos_o.

Parameters
    kd     texture (e.g. {'type': 'rgb', 'value': ...} or a 'bitmap'): the diffuse albedo,
           base colour x (1 - metallic). A plain RGB triple is also accepted.
    f0     RGB: Schlick's F0 = 0.04 (1 - metallic) + base colour x metallic.
    alpha  float: GGX alpha (across the anisotropy direction where anisotropic).
    alpha_t   float (optional): GGX alpha along the anisotropy direction.
    rotation  float (optional, radians, default 0): the anisotropy direction's angle from s
              towards t.

Importance sampling: a one-sample mixture of cosine-weighted hemisphere sampling (probability
1 - p_spec) and GGX visible-normal sampling (Heitz 2018, Mitsuba's MicrofacetDistribution with
sample_visible=True) reflected about the sampled micro-normal (probability p_spec), where
p_spec = mean(F0) / (mean(F0) + mean(kd)) clamped to [0.1, 1] (1 when kd = 0). The pdf is the
mixture's full pdf, so the estimator is unbiased for any p_spec.

Usage:
    import mitsuba as mi; mi.set_variant('llvm_ad_rgb')
    import diffuse_ggx; diffuse_ggx.register()
    bsdf = mi.load_dict({'type': 'diffuse_ggx', 'kd': {'type': 'rgb', 'value': [0.7, 0.7, 0.7]},
                         'f0': [0.04, 0.04, 0.04], 'alpha': 1.0})
"""
import math

import drjit as dr
import mitsuba as mi


def _as_texture(value):
    """A texture object for `value` (a Texture, or an RGB triple / scalar)."""
    if isinstance(value, mi.Texture):
        return value
    # (Mitsuba's dictionary parser turns a nested {'type': 'rgb'} into a plain colour)
    if isinstance(value, (int, float)):
        value = [float(value)] * 3
    return mi.load_dict({'type': 'rgb', 'value': [float(v) for v in value]})


def _rgb(value):
    if isinstance(value, (int, float)):
        return [float(value)] * 3
    return [float(v) for v in value]


class DiffuseGGX(mi.BSDF):
    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.kd = _as_texture(props['kd'])
        self.f0_rgb = _rgb(props['f0'])
        self.f0 = mi.Color3f(*self.f0_rgb)
        self.alpha_value = float(props['alpha'])
        self.alpha = mi.Float(self.alpha_value)
        self.anisotropic = props.has_property('alpha_t')
        self.alpha_t_value = float(props['alpha_t']) if self.anisotropic else self.alpha_value
        rotation = float(props['rotation']) if props.has_property('rotation') else 0.0
        self.rot_cos, self.rot_sin = math.cos(rotation), math.sin(rotation)

        # Probability of sampling the specular lobe (a constant per material).
        ms = sum(self.f0_rgb) / 3.0
        md = float(dr.mean(self.kd.mean(), axis=None)[0]) if dr.is_array_v(self.kd.mean()) \
            else float(self.kd.mean())
        if md <= 0.0:
            self.p_spec = 1.0
        else:
            self.p_spec = min(1.0, max(0.1, ms / (ms + md)))

        flags_d = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide
        flags_g = mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
        if self.kd.is_spatially_varying():
            flags_d = flags_d | mi.BSDFFlags.SpatiallyVarying
        self.m_components = [flags_d, flags_g]
        self.m_flags = flags_d | flags_g

    # ---- the BRDF --------------------------------------------------------------------------

    def _ggx_d(self, cos_h):
        a2 = dr.square(self.alpha)
        c2 = dr.square(cos_h)
        return a2 / (dr.pi * dr.square(c2 * (a2 - 1.0) + 1.0))

    def _smith_g1(self, cos_v):
        # G1 = 2 / (1 + sqrt(1 + a^2 tan^2)), tan^2 = (1 - c^2) / c^2
        c2 = dr.square(cos_v)
        tan2 = dr.maximum(1.0 - c2, 0.0) / c2
        return 2.0 / (1.0 + dr.sqrt(1.0 + dr.square(self.alpha) * tan2))

    def _distribution(self):
        """Mitsuba's GGX with visible-normal sampling: (alpha_t, alpha) in the rotated frame."""
        if self.anisotropic:
            return mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha_t_value,
                                             self.alpha_value, True)
        return mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha, True)

    def _rotate(self, v, sign=1.0):
        """v in the frame whose x axis is the anisotropy direction (sign -1: back)."""
        if not self.anisotropic:
            return v
        c, s = self.rot_cos, sign * self.rot_sin
        return mi.Vector3f(c * v.x + s * v.y, -s * v.x + c * v.y, v.z)

    def _f_cos(self, si, wo, active):
        """f(wi, wo) * cos_o in the local shading frame, 0 unless both cosines are > 0."""
        wi = si.wi
        cos_i = mi.Frame3f.cos_theta(wi)
        cos_o = mi.Frame3f.cos_theta(wo)
        active = active & (cos_i > 0.0) & (cos_o > 0.0)

        kd = self.kd.eval(si, active)
        h = dr.normalize(wi + wo)
        wi_h = dr.clip(dr.dot(wi, h), 0.0, 1.0)
        fresnel = self.f0 + (1.0 - self.f0) * dr.power(1.0 - wi_h, 5.0)
        if self.anisotropic:
            distr = self._distribution()
            hr = self._rotate(h)
            d = distr.eval(hr)
            g = distr.G(self._rotate(wi), self._rotate(wo), hr)
        else:
            d = self._ggx_d(mi.Frame3f.cos_theta(h))
            g = self._smith_g1(cos_i) * self._smith_g1(cos_o)
        spec = fresnel * (d * g / (4.0 * cos_i * cos_o))
        value = (kd * dr.inv_pi + spec) * cos_o
        return dr.select(active, value, 0.0), active

    def _pdf(self, si, wo, active):
        wi = si.wi
        cos_i = mi.Frame3f.cos_theta(wi)
        cos_o = mi.Frame3f.cos_theta(wo)
        active = active & (cos_i > 0.0) & (cos_o > 0.0)
        pdf_d = cos_o * dr.inv_pi
        m = dr.normalize(wi + wo)
        distr = self._distribution()
        # visible-normal pdf of m, times the Jacobian of the reflection d(wo)/d(m) = 1/(4 wo.m)
        pdf_g = distr.pdf(self._rotate(wi), self._rotate(m)) / (4.0 * dr.abs(dr.dot(wo, m)))
        pdf = (1.0 - self.p_spec) * pdf_d + self.p_spec * pdf_g
        return dr.select(active, pdf, 0.0)

    # ---- the mi.BSDF interface ------------------------------------------------------------

    def eval(self, ctx, si, wo, active=True):
        value, _ = self._f_cos(si, wo, active)
        return value

    def pdf(self, ctx, si, wo, active=True):
        return self._pdf(si, wo, active)

    def eval_pdf(self, ctx, si, wo, active=True):
        value, _ = self._f_cos(si, wo, active)
        return value, self._pdf(si, wo, active)

    def sample(self, ctx, si, sample1, sample2, active=True):
        wi = si.wi
        active = active & (mi.Frame3f.cos_theta(wi) > 0.0)

        choose_spec = sample1 < self.p_spec
        wo_d = mi.warp.square_to_cosine_hemisphere(sample2)
        distr = self._distribution()
        m, _ = distr.sample(self._rotate(wi), sample2)
        m = self._rotate(m, -1.0)
        wo_g = mi.reflect(wi, m)
        wo = dr.select(choose_spec, wo_g, wo_d)

        value, ok = self._f_cos(si, wo, active)
        pdf = self._pdf(si, wo, active)
        ok = ok & (pdf > 0.0)

        bs = dr.zeros(mi.BSDFSample3f)
        bs.wo = wo
        bs.pdf = dr.select(ok, pdf, 0.0)
        bs.eta = 1.0
        bs.sampled_type = mi.UInt32(dr.select(choose_spec,
                                              mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                              mi.UInt32(+mi.BSDFFlags.DiffuseReflection)))
        bs.sampled_component = dr.select(choose_spec, mi.UInt32(1), mi.UInt32(0))
        weight = dr.select(ok, value / dr.select(ok, pdf, 1.0), 0.0)
        return bs, weight

    def eval_diffuse_reflectance(self, si, active=True):
        return self.kd.eval(si, active)

    def traverse(self, callback):
        pass

    def parameters_changed(self, keys):
        pass

    def to_string(self):
        return ('DiffuseGGX[kd=%s, f0=%s, alpha=%g, alpha_t=%g, rotation=(%g, %g), p_spec=%g]'
                % (self.kd, self.f0_rgb, self.alpha_value, self.alpha_t_value, self.rot_cos,
                   self.rot_sin, self.p_spec))


def register():
    """Registers the plugin under the name 'diffuse_ggx' (call after mi.set_variant)."""
    mi.register_bsdf('diffuse_ggx', lambda props: DiffuseGGX(props))
