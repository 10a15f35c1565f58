from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.shadowing_spec import ShadowingSpec
from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.spectral_spec import SpectralSpec





T = TypeVar("T", bound="MaterialObject")



@_attrs_define
class MaterialObject:
    """ A material with its model parameters. Which parameters are allowed depends on `model`:
    - `seed-microfacet`: `kd`, `km`, `slope_rms`, `n`, `k` (the paper's Eqs. 6–8), optional
      `normalised`
    - `lambert`: `albedo`
    - `rough-conductor`: `alpha`, `n`, `k`, optional `kd` and `shadowing` (Beckmann + Smith,
      as Mitsuba 3's `roughconductor`; pbrt's Smith form with `shadowing: correlated`)
    - `ashikhmin-shirley`: `rd`, `rs`, `nu`, `nv`, optional `tangent`

        Attributes:
            name (str): Name used by `usemtl` and built-in objects.
            model (None | str | Unset): `seed-microfacet`, `lambert`, `rough-conductor` or `ashikhmin-shirley`.
            preset (None | str | Unset): Use a preset's model and parameters under this material's name.
            kd (float | None | Unset): Diffuse coefficient k^D (dimensionless, 0..1).
            km (float | None | Unset): Specular coefficient k^M (dimensionless, >= 0).
            slope_rms (float | None | Unset): RMS microfacet slope δ (dimensionless, > 0).
            normalised (bool | None | Unset): `seed-microfacet` only. `false` (default): k^M as the paper's Eq. 8 writes it,
                whose
                lobe reflects ≈ 4π·k^M·F(0) of the light at normal incidence (a smooth lobe; more
                than 1 for k^M above ~0.08). `true`: k^M (0..1) is the specular lobe's albedo at
                normal incidence — Eq. 8's k^M is k^M / a(δ, n, k), a the lobe's albedo with
                k^M = 1 — so kd + km ≤ 1 reflects no more than it receives there.
            n (float | None | Unset): Real part of the complex refractive index.
            k (float | None | Unset): Imaginary part (extinction coefficient) of the refractive index.
            albedo (float | None | Unset): Lambertian albedo (0..1).
            alpha (float | None | Unset): Beckmann roughness α of `rough-conductor` (> 0).
            shadowing (None | ShadowingSpec | Unset):
            rd (float | None | Unset): Ashikhmin–Shirley diffuse reflectance R_d (0..1).
            rs (float | None | Unset): Ashikhmin–Shirley specular reflectance at normal incidence R_s (0..1).
            nu (float | None | Unset): Ashikhmin–Shirley Phong exponent along the face tangent (> 0): see `tangent`.
            nv (float | None | Unset): Ashikhmin–Shirley Phong exponent along the face bitangent (> 0).
            tangent (list[float] | None | Unset): Ashikhmin–Shirley only: the body-frame direction [x, y, z] (any length)
                along which
                `nu` runs, e.g. a brushed or grooved direction. Each face takes it projected onto
                its plane; a face whose normal is within 8.1° of it takes instead a fixed direction
                perpendicular to it. Default [1, 0, 0], the body's x axis.
            two_sided (bool | None | Unset): Thin sheet lit and seen from both sides (solar panels). Default false.
            spectral (None | SpectralSpec | Unset):
     """

    name: str
    model: None | str | Unset = UNSET
    preset: None | str | Unset = UNSET
    kd: float | None | Unset = UNSET
    km: float | None | Unset = UNSET
    slope_rms: float | None | Unset = UNSET
    normalised: bool | None | Unset = UNSET
    n: float | None | Unset = UNSET
    k: float | None | Unset = UNSET
    albedo: float | None | Unset = UNSET
    alpha: float | None | Unset = UNSET
    shadowing: None | ShadowingSpec | Unset = UNSET
    rd: float | None | Unset = UNSET
    rs: float | None | Unset = UNSET
    nu: float | None | Unset = UNSET
    nv: float | None | Unset = UNSET
    tangent: list[float] | None | Unset = UNSET
    two_sided: bool | None | Unset = UNSET
    spectral: None | SpectralSpec | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.spectral_spec import SpectralSpec # noqa: PLC0415
        name = self.name

        model: None | str | Unset
        if isinstance(self.model, Unset):
            model = UNSET
        else:
            model = self.model

        preset: None | str | Unset
        if isinstance(self.preset, Unset):
            preset = UNSET
        else:
            preset = self.preset

        kd: float | None | Unset
        if isinstance(self.kd, Unset):
            kd = UNSET
        else:
            kd = self.kd

        km: float | None | Unset
        if isinstance(self.km, Unset):
            km = UNSET
        else:
            km = self.km

        slope_rms: float | None | Unset
        if isinstance(self.slope_rms, Unset):
            slope_rms = UNSET
        else:
            slope_rms = self.slope_rms

        normalised: bool | None | Unset
        if isinstance(self.normalised, Unset):
            normalised = UNSET
        else:
            normalised = self.normalised

        n: float | None | Unset
        if isinstance(self.n, Unset):
            n = UNSET
        else:
            n = self.n

        k: float | None | Unset
        if isinstance(self.k, Unset):
            k = UNSET
        else:
            k = self.k

        albedo: float | None | Unset
        if isinstance(self.albedo, Unset):
            albedo = UNSET
        else:
            albedo = self.albedo

        alpha: float | None | Unset
        if isinstance(self.alpha, Unset):
            alpha = UNSET
        else:
            alpha = self.alpha

        shadowing: None | str | Unset
        if isinstance(self.shadowing, Unset):
            shadowing = UNSET
        elif isinstance(self.shadowing, ShadowingSpec):
            shadowing = self.shadowing.value
        else:
            shadowing = self.shadowing

        rd: float | None | Unset
        if isinstance(self.rd, Unset):
            rd = UNSET
        else:
            rd = self.rd

        rs: float | None | Unset
        if isinstance(self.rs, Unset):
            rs = UNSET
        else:
            rs = self.rs

        nu: float | None | Unset
        if isinstance(self.nu, Unset):
            nu = UNSET
        else:
            nu = self.nu

        nv: float | None | Unset
        if isinstance(self.nv, Unset):
            nv = UNSET
        else:
            nv = self.nv

        tangent: list[float] | None | Unset
        if isinstance(self.tangent, Unset):
            tangent = UNSET
        elif isinstance(self.tangent, list):
            tangent = self.tangent


        else:
            tangent = self.tangent

        two_sided: bool | None | Unset
        if isinstance(self.two_sided, Unset):
            two_sided = UNSET
        else:
            two_sided = self.two_sided

        spectral: dict[str, Any] | None | Unset
        if isinstance(self.spectral, Unset):
            spectral = UNSET
        elif isinstance(self.spectral, SpectralSpec):
            spectral = self.spectral.to_dict()
        else:
            spectral = self.spectral


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "name": name,
        })
        if model is not UNSET:
            field_dict["model"] = model
        if preset is not UNSET:
            field_dict["preset"] = preset
        if kd is not UNSET:
            field_dict["kd"] = kd
        if km is not UNSET:
            field_dict["km"] = km
        if slope_rms is not UNSET:
            field_dict["slope_rms"] = slope_rms
        if normalised is not UNSET:
            field_dict["normalised"] = normalised
        if n is not UNSET:
            field_dict["n"] = n
        if k is not UNSET:
            field_dict["k"] = k
        if albedo is not UNSET:
            field_dict["albedo"] = albedo
        if alpha is not UNSET:
            field_dict["alpha"] = alpha
        if shadowing is not UNSET:
            field_dict["shadowing"] = shadowing
        if rd is not UNSET:
            field_dict["rd"] = rd
        if rs is not UNSET:
            field_dict["rs"] = rs
        if nu is not UNSET:
            field_dict["nu"] = nu
        if nv is not UNSET:
            field_dict["nv"] = nv
        if tangent is not UNSET:
            field_dict["tangent"] = tangent
        if two_sided is not UNSET:
            field_dict["two_sided"] = two_sided
        if spectral is not UNSET:
            field_dict["spectral"] = spectral

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.spectral_spec import SpectralSpec # noqa: PLC0415
        d = dict(src_dict)
        name = d.pop("name")

        def _parse_model(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        model = _parse_model(d.pop("model", UNSET))


        def _parse_preset(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        preset = _parse_preset(d.pop("preset", UNSET))


        def _parse_kd(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        kd = _parse_kd(d.pop("kd", UNSET))


        def _parse_km(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        km = _parse_km(d.pop("km", UNSET))


        def _parse_slope_rms(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        slope_rms = _parse_slope_rms(d.pop("slope_rms", UNSET))


        def _parse_normalised(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        normalised = _parse_normalised(d.pop("normalised", UNSET))


        def _parse_n(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        n = _parse_n(d.pop("n", UNSET))


        def _parse_k(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        k = _parse_k(d.pop("k", UNSET))


        def _parse_albedo(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        albedo = _parse_albedo(d.pop("albedo", UNSET))


        def _parse_alpha(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        alpha = _parse_alpha(d.pop("alpha", UNSET))


        def _parse_shadowing(data: object) -> None | ShadowingSpec | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, str):
                    raise TypeError()
                shadowing_type_0 = ShadowingSpec(data)



                return shadowing_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | ShadowingSpec | Unset, data)

        shadowing = _parse_shadowing(d.pop("shadowing", UNSET))


        def _parse_rd(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        rd = _parse_rd(d.pop("rd", UNSET))


        def _parse_rs(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        rs = _parse_rs(d.pop("rs", UNSET))


        def _parse_nu(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        nu = _parse_nu(d.pop("nu", UNSET))


        def _parse_nv(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        nv = _parse_nv(d.pop("nv", UNSET))


        def _parse_tangent(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                tangent_type_0 = cast(list[float], data)

                return tangent_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        tangent = _parse_tangent(d.pop("tangent", UNSET))


        def _parse_two_sided(data: object) -> bool | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(bool | None | Unset, data)

        two_sided = _parse_two_sided(d.pop("two_sided", UNSET))


        def _parse_spectral(data: object) -> None | SpectralSpec | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                spectral_type_0 = SpectralSpec.from_dict(data)



                return spectral_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | SpectralSpec | Unset, data)

        spectral = _parse_spectral(d.pop("spectral", UNSET))


        material_object = cls(
            name=name,
            model=model,
            preset=preset,
            kd=kd,
            km=km,
            slope_rms=slope_rms,
            normalised=normalised,
            n=n,
            k=k,
            albedo=albedo,
            alpha=alpha,
            shadowing=shadowing,
            rd=rd,
            rs=rs,
            nu=nu,
            nv=nv,
            tangent=tangent,
            two_sided=two_sided,
            spectral=spectral,
        )

        return material_object

