from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="IlluminationSpec")



@_attrs_define
class IlluminationSpec:
    """ Illumination: spectral band, Sun temperature, earthshine.

        Attributes:
            band_um (list[float] | None | Unset): Spectral band [λ1, λ2] in µm, every wavelength in it counted alike.
                Default
                [0.4, 0.7]. Its magnitudes put the Sun at 1 AU at −26.74 (V-like). The Sun's
                irradiance in it at 1 AU must be at least 1e-200 W/m² (not so only far in the Wien
                tail of a cold Sun). Not with `band`.
            band (None | str | Unset): A standard passband instead of `band_um`, integrated through its tabulated response
                (photon-weighted, as a CCD counts): `V`, `B` (Johnson, Bessell 1990), `R` (Cousins,
                Bessell 1990), `G` (Gaia EDR3), `g`, `r`, `i` (SDSS, Doi et al. 2010; AB), `clear`
                (an unfiltered silicon CCD: the Kepler photometer's response, 0.42–0.905 µm). Its
                magnitudes take the Sun's magnitude in that band as zero point: V −26.76 and B
                −26.13 (Willmer 2018, ApJS 236, 47), R −27.13, G −26.89, clear −26.88 (Vega),
                g −26.46, r −26.93, i −27.04 (AB), computed from the CALSPEC solar spectrum
                (docs/physics.md §10). Example: V.
            sun_temperature_k (float | None | Unset): Sun blackbody temperature in K. Default 5900 (the paper's value). Used
                with
                `solar_spectrum: planck`.
            solar_spectrum (None | str | Unset): The solar spectrum integrated through the band: `planck` (default: a
                blackbody at
                `sun_temperature_k`) or `calspec` (the tabulated CALSPEC solar reference spectrum,
                Colina, Bohlin & Castelli 1996, 0.1195–2.70 µm; the band must lie within it).
                Magnitudes of wavelength-independent materials do not depend on it: E and the
                Sun's in-band irradiance change alike. Example: planck.
            earthshine (None | str | Unset): `off`, `sphere` (the default: the sunlit Lambertian Earth over its visible cap,
                with
                its distance and phase) or `seed` (the paper's Eq. 3: ρ·E_s as one parallel beam
                from the Earth's direction at any distance and Earth phase — to reproduce the
                paper; at GEO it is 59× the sphere at full Earth). Without `earth` in the epochs,
                no earthshine.
            earth_albedo (float | None | Unset): Earth's Bond albedo ρ. Default 0.35.
     """

    band_um: list[float] | None | Unset = UNSET
    band: None | str | Unset = UNSET
    sun_temperature_k: float | None | Unset = UNSET
    solar_spectrum: None | str | Unset = UNSET
    earthshine: None | str | Unset = UNSET
    earth_albedo: float | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        band_um: list[float] | None | Unset
        if isinstance(self.band_um, Unset):
            band_um = UNSET
        elif isinstance(self.band_um, list):
            band_um = self.band_um


        else:
            band_um = self.band_um

        band: None | str | Unset
        if isinstance(self.band, Unset):
            band = UNSET
        else:
            band = self.band

        sun_temperature_k: float | None | Unset
        if isinstance(self.sun_temperature_k, Unset):
            sun_temperature_k = UNSET
        else:
            sun_temperature_k = self.sun_temperature_k

        solar_spectrum: None | str | Unset
        if isinstance(self.solar_spectrum, Unset):
            solar_spectrum = UNSET
        else:
            solar_spectrum = self.solar_spectrum

        earthshine: None | str | Unset
        if isinstance(self.earthshine, Unset):
            earthshine = UNSET
        else:
            earthshine = self.earthshine

        earth_albedo: float | None | Unset
        if isinstance(self.earth_albedo, Unset):
            earth_albedo = UNSET
        else:
            earth_albedo = self.earth_albedo


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if band_um is not UNSET:
            field_dict["band_um"] = band_um
        if band is not UNSET:
            field_dict["band"] = band
        if sun_temperature_k is not UNSET:
            field_dict["sun_temperature_k"] = sun_temperature_k
        if solar_spectrum is not UNSET:
            field_dict["solar_spectrum"] = solar_spectrum
        if earthshine is not UNSET:
            field_dict["earthshine"] = earthshine
        if earth_albedo is not UNSET:
            field_dict["earth_albedo"] = earth_albedo

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_band_um(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                band_um_type_0 = cast(list[float], data)

                return band_um_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        band_um = _parse_band_um(d.pop("band_um", UNSET))


        def _parse_band(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        band = _parse_band(d.pop("band", UNSET))


        def _parse_sun_temperature_k(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sun_temperature_k = _parse_sun_temperature_k(d.pop("sun_temperature_k", UNSET))


        def _parse_solar_spectrum(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        solar_spectrum = _parse_solar_spectrum(d.pop("solar_spectrum", UNSET))


        def _parse_earthshine(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        earthshine = _parse_earthshine(d.pop("earthshine", UNSET))


        def _parse_earth_albedo(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        earth_albedo = _parse_earth_albedo(d.pop("earth_albedo", UNSET))


        illumination_spec = cls(
            band_um=band_um,
            band=band,
            sun_temperature_k=sun_temperature_k,
            solar_spectrum=solar_spectrum,
            earthshine=earthshine,
            earth_albedo=earth_albedo,
        )

        return illumination_spec

