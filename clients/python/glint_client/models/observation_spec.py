from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ObservationSpec")



@_attrs_define
class ObservationSpec:
    """ A telescope, its detector and the sky.

        Attributes:
            aperture_m (float): Aperture diameter, m (0 < D ≤ 50). Example: 0.5.
            exposure_s (float): Exposure time, s (0 < t ≤ 1e5). Example: 1.0.
            obstruction (float | None | Unset): Central obstruction as a fraction of the diameter, 0 to 0.99. Default 0.
            quantum_efficiency (float | None | Unset): Detector quantum efficiency in the band, 0 to 1 (exclusive of 0).
                Default 1.
            throughput (float | None | Unset): Optics and filter throughput beyond the band's own response, 0 to 1
                (exclusive of
                0). Default 1.
            pixel_scale_arcsec (float | None | Unset): Pixel scale, arcsec per pixel (> 0). Default 1.
            seeing_fwhm_arcsec (float | None | Unset): Seeing: FWHM of the Gaussian star image, arcsec (> 0). Default 2.
            aperture_radius_arcsec (float | None | Unset): Radius of the circular photometric aperture, arcsec (> 0).
                Default the seeing
                FWHM (which holds 93.75 % of a Gaussian image).
            read_noise_e (float | None | Unset): Read noise, e⁻ rms per pixel (≥ 0). Default 0.
            dark_e_per_s (float | None | Unset): Dark current, e⁻/s per pixel (≥ 0). Default 0.
            gain_e_per_adu (float | None | Unset): Gain, e⁻ per ADU (> 0). Default 1.
            full_well_e (float | None | Unset): Full well, e⁻ (> 0): the brightest pixel at or above it is saturated.
                Default:
                none (never saturated).
            sky_mag_per_arcsec2 (float | None | Unset): Sky brightness in the band, mag/arcsec², as measured at the site
                (−10 to 40).
                Default: no sky. Example: 21.0.
            airmass (float | None | Unset): Airmass (1 to 40). Default 1.
            extinction_mag_per_airmass (float | None | Unset): Atmospheric extinction, mag per airmass (0 to 10). Default 0.
            seed (int | None | Unset): Seed of the noisy samples: the same seed gives the same samples. Default 0.
     """

    aperture_m: float
    exposure_s: float
    obstruction: float | None | Unset = UNSET
    quantum_efficiency: float | None | Unset = UNSET
    throughput: float | None | Unset = UNSET
    pixel_scale_arcsec: float | None | Unset = UNSET
    seeing_fwhm_arcsec: float | None | Unset = UNSET
    aperture_radius_arcsec: float | None | Unset = UNSET
    read_noise_e: float | None | Unset = UNSET
    dark_e_per_s: float | None | Unset = UNSET
    gain_e_per_adu: float | None | Unset = UNSET
    full_well_e: float | None | Unset = UNSET
    sky_mag_per_arcsec2: float | None | Unset = UNSET
    airmass: float | None | Unset = UNSET
    extinction_mag_per_airmass: float | None | Unset = UNSET
    seed: int | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        aperture_m = self.aperture_m

        exposure_s = self.exposure_s

        obstruction: float | None | Unset
        if isinstance(self.obstruction, Unset):
            obstruction = UNSET
        else:
            obstruction = self.obstruction

        quantum_efficiency: float | None | Unset
        if isinstance(self.quantum_efficiency, Unset):
            quantum_efficiency = UNSET
        else:
            quantum_efficiency = self.quantum_efficiency

        throughput: float | None | Unset
        if isinstance(self.throughput, Unset):
            throughput = UNSET
        else:
            throughput = self.throughput

        pixel_scale_arcsec: float | None | Unset
        if isinstance(self.pixel_scale_arcsec, Unset):
            pixel_scale_arcsec = UNSET
        else:
            pixel_scale_arcsec = self.pixel_scale_arcsec

        seeing_fwhm_arcsec: float | None | Unset
        if isinstance(self.seeing_fwhm_arcsec, Unset):
            seeing_fwhm_arcsec = UNSET
        else:
            seeing_fwhm_arcsec = self.seeing_fwhm_arcsec

        aperture_radius_arcsec: float | None | Unset
        if isinstance(self.aperture_radius_arcsec, Unset):
            aperture_radius_arcsec = UNSET
        else:
            aperture_radius_arcsec = self.aperture_radius_arcsec

        read_noise_e: float | None | Unset
        if isinstance(self.read_noise_e, Unset):
            read_noise_e = UNSET
        else:
            read_noise_e = self.read_noise_e

        dark_e_per_s: float | None | Unset
        if isinstance(self.dark_e_per_s, Unset):
            dark_e_per_s = UNSET
        else:
            dark_e_per_s = self.dark_e_per_s

        gain_e_per_adu: float | None | Unset
        if isinstance(self.gain_e_per_adu, Unset):
            gain_e_per_adu = UNSET
        else:
            gain_e_per_adu = self.gain_e_per_adu

        full_well_e: float | None | Unset
        if isinstance(self.full_well_e, Unset):
            full_well_e = UNSET
        else:
            full_well_e = self.full_well_e

        sky_mag_per_arcsec2: float | None | Unset
        if isinstance(self.sky_mag_per_arcsec2, Unset):
            sky_mag_per_arcsec2 = UNSET
        else:
            sky_mag_per_arcsec2 = self.sky_mag_per_arcsec2

        airmass: float | None | Unset
        if isinstance(self.airmass, Unset):
            airmass = UNSET
        else:
            airmass = self.airmass

        extinction_mag_per_airmass: float | None | Unset
        if isinstance(self.extinction_mag_per_airmass, Unset):
            extinction_mag_per_airmass = UNSET
        else:
            extinction_mag_per_airmass = self.extinction_mag_per_airmass

        seed: int | None | Unset
        if isinstance(self.seed, Unset):
            seed = UNSET
        else:
            seed = self.seed


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "aperture_m": aperture_m,
            "exposure_s": exposure_s,
        })
        if obstruction is not UNSET:
            field_dict["obstruction"] = obstruction
        if quantum_efficiency is not UNSET:
            field_dict["quantum_efficiency"] = quantum_efficiency
        if throughput is not UNSET:
            field_dict["throughput"] = throughput
        if pixel_scale_arcsec is not UNSET:
            field_dict["pixel_scale_arcsec"] = pixel_scale_arcsec
        if seeing_fwhm_arcsec is not UNSET:
            field_dict["seeing_fwhm_arcsec"] = seeing_fwhm_arcsec
        if aperture_radius_arcsec is not UNSET:
            field_dict["aperture_radius_arcsec"] = aperture_radius_arcsec
        if read_noise_e is not UNSET:
            field_dict["read_noise_e"] = read_noise_e
        if dark_e_per_s is not UNSET:
            field_dict["dark_e_per_s"] = dark_e_per_s
        if gain_e_per_adu is not UNSET:
            field_dict["gain_e_per_adu"] = gain_e_per_adu
        if full_well_e is not UNSET:
            field_dict["full_well_e"] = full_well_e
        if sky_mag_per_arcsec2 is not UNSET:
            field_dict["sky_mag_per_arcsec2"] = sky_mag_per_arcsec2
        if airmass is not UNSET:
            field_dict["airmass"] = airmass
        if extinction_mag_per_airmass is not UNSET:
            field_dict["extinction_mag_per_airmass"] = extinction_mag_per_airmass
        if seed is not UNSET:
            field_dict["seed"] = seed

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        aperture_m = d.pop("aperture_m")

        exposure_s = d.pop("exposure_s")

        def _parse_obstruction(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        obstruction = _parse_obstruction(d.pop("obstruction", UNSET))


        def _parse_quantum_efficiency(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        quantum_efficiency = _parse_quantum_efficiency(d.pop("quantum_efficiency", UNSET))


        def _parse_throughput(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        throughput = _parse_throughput(d.pop("throughput", UNSET))


        def _parse_pixel_scale_arcsec(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        pixel_scale_arcsec = _parse_pixel_scale_arcsec(d.pop("pixel_scale_arcsec", UNSET))


        def _parse_seeing_fwhm_arcsec(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        seeing_fwhm_arcsec = _parse_seeing_fwhm_arcsec(d.pop("seeing_fwhm_arcsec", UNSET))


        def _parse_aperture_radius_arcsec(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        aperture_radius_arcsec = _parse_aperture_radius_arcsec(d.pop("aperture_radius_arcsec", UNSET))


        def _parse_read_noise_e(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        read_noise_e = _parse_read_noise_e(d.pop("read_noise_e", UNSET))


        def _parse_dark_e_per_s(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        dark_e_per_s = _parse_dark_e_per_s(d.pop("dark_e_per_s", UNSET))


        def _parse_gain_e_per_adu(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        gain_e_per_adu = _parse_gain_e_per_adu(d.pop("gain_e_per_adu", UNSET))


        def _parse_full_well_e(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        full_well_e = _parse_full_well_e(d.pop("full_well_e", UNSET))


        def _parse_sky_mag_per_arcsec2(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        sky_mag_per_arcsec2 = _parse_sky_mag_per_arcsec2(d.pop("sky_mag_per_arcsec2", UNSET))


        def _parse_airmass(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        airmass = _parse_airmass(d.pop("airmass", UNSET))


        def _parse_extinction_mag_per_airmass(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        extinction_mag_per_airmass = _parse_extinction_mag_per_airmass(d.pop("extinction_mag_per_airmass", UNSET))


        def _parse_seed(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        seed = _parse_seed(d.pop("seed", UNSET))


        observation_spec = cls(
            aperture_m=aperture_m,
            exposure_s=exposure_s,
            obstruction=obstruction,
            quantum_efficiency=quantum_efficiency,
            throughput=throughput,
            pixel_scale_arcsec=pixel_scale_arcsec,
            seeing_fwhm_arcsec=seeing_fwhm_arcsec,
            aperture_radius_arcsec=aperture_radius_arcsec,
            read_noise_e=read_noise_e,
            dark_e_per_s=dark_e_per_s,
            gain_e_per_adu=gain_e_per_adu,
            full_well_e=full_well_e,
            sky_mag_per_arcsec2=sky_mag_per_arcsec2,
            airmass=airmass,
            extinction_mag_per_airmass=extinction_mag_per_airmass,
            seed=seed,
        )

        return observation_spec

