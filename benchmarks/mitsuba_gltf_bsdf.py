"""rcsplat's BRDF (kernels/brdf.h: glTF's metallic-roughness model with the diffuse base weighted by the view angle's
Fresnel) as a Mitsuba 3 BSDF plugin, so that benchmarks/mitsuba_peer.py compares light transport, not two material
models: f = (1 - m)(1 - F_d(n.v)) base / pi + F(v.h) D(h) V(l, v), with GGX D, height-correlated Smith V and Schlick F
(F0 = (1 - m) 0.04 + m base). Sampling mixes a cosine lobe and GGX visible normals. One-sided: wrap it in `twosided`.

  register(mi)  # after mi.set_variant(...); then {"type": "rcsplat_gltf", "base_color": ..., "metallic", "roughness"}
"""
import math


def register(mi):
    import drjit as dr

    class RcsplatGltfBsdf(mi.BSDF):
        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            base = props["base_color"]
            # An "rgb" value arrives as a colour, a bitmap as a texture: make both textures.
            self.base = base if isinstance(base, mi.Texture) else mi.load_dict(
                {"type": "rgb", "value": [float(base[0]), float(base[1]), float(base[2])]})
            self.metallic = float(props["metallic"])
            self.alpha = max(float(props["roughness"]) ** 2, 1e-3)
            # The share of samples given to the GGX lobe: its Fresnel weight at normal incidence, at least 10%.
            self.spec_share = max(0.1, min(0.9, 0.04 + 0.96 * self.metallic))
            reflection = mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide
            self.m_components = [mi.BSDFFlags.DiffuseReflection | mi.BSDFFlags.FrontSide,
                                 mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide]
            self.m_flags = reflection

        def _distribution(self):
            return mi.MicrofacetDistribution(mi.MicrofacetType.GGX, self.alpha, True)

        def _eval(self, si, wo, active):
            cos_v, cos_l = mi.Frame3f.cos_theta(si.wi), mi.Frame3f.cos_theta(wo)
            active = active & (cos_v > 0) & (cos_l > 0)
            base = self.base.eval(si, active)
            m, a2 = self.metallic, self.alpha * self.alpha
            weight_v = dr.power(1.0 - cos_v, 5.0)
            diffuse = (1.0 - m) * (1.0 - (0.04 + 0.96 * weight_v)) * base * (1.0 / math.pi)
            h = dr.normalize(si.wi + wo)
            cos_h = mi.Frame3f.cos_theta(h)
            d = a2 / (math.pi * dr.square(cos_h * cos_h * (a2 - 1.0) + 1.0))
            vis = 0.5 / (cos_l * dr.sqrt(cos_v * cos_v * (1.0 - a2) + a2) + cos_v * dr.sqrt(cos_l * cos_l * (1.0 - a2) + a2))
            weight_h = dr.power(1.0 - dr.clip(dr.dot(si.wi, h), 0.0, 1.0), 5.0)
            f0 = (1.0 - m) * 0.04 + m * base
            fresnel = f0 + (1.0 - f0) * weight_h
            value = (diffuse + fresnel * (d * vis)) * cos_l
            return dr.select(active, value, 0.0), active

        def _pdf(self, si, wo, active):
            cos_l = mi.Frame3f.cos_theta(wo)
            active = active & (mi.Frame3f.cos_theta(si.wi) > 0) & (cos_l > 0)
            h = dr.normalize(si.wi + wo)
            spec = self._distribution().pdf(si.wi, h) / (4.0 * dr.abs(dr.dot(wo, h)))
            pdf = (1.0 - self.spec_share) * cos_l * (1.0 / math.pi) + self.spec_share * spec
            return dr.select(active, pdf, 0.0)

        def eval(self, ctx, si, wo, active=True):
            return self._eval(si, wo, active)[0]

        def pdf(self, ctx, si, wo, active=True):
            return self._pdf(si, wo, active)

        def eval_pdf(self, ctx, si, wo, active=True):
            return self._eval(si, wo, active)[0], self._pdf(si, wo, active)

        def sample(self, ctx, si, sample1, sample2, active=True):
            choose_spec = sample1 < self.spec_share
            wo_diffuse = mi.warp.square_to_cosine_hemisphere(sample2)
            normal, _ = self._distribution().sample(si.wi, sample2)
            wo_spec = mi.reflect(si.wi, normal)
            bs = dr.zeros(mi.BSDFSample3f)
            bs.wo = dr.select(choose_spec, wo_spec, wo_diffuse)
            bs.eta = 1.0
            bs.sampled_component = dr.select(choose_spec, mi.UInt32(1), mi.UInt32(0))
            bs.sampled_type = dr.select(choose_spec, mi.UInt32(+mi.BSDFFlags.GlossyReflection),
                                        mi.UInt32(+mi.BSDFFlags.DiffuseReflection))
            value, ok = self._eval(si, bs.wo, active)
            bs.pdf = self._pdf(si, bs.wo, active)
            ok = ok & (bs.pdf > 0)
            return bs, dr.select(ok, value / dr.maximum(bs.pdf, 1e-20), 0.0)

        def traverse(self, callback):
            pass

        def to_string(self):
            return f"RcsplatGltfBsdf[metallic={self.metallic}, alpha={self.alpha}]"

    mi.register_bsdf("rcsplat_gltf", lambda props: RcsplatGltfBsdf(props))
