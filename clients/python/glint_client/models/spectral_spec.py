from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="SpectralSpec")



@_attrs_define
class SpectralSpec:
    """ A material's parameters against wavelength: linear between the points, constant
    beyond the first and last.

        Attributes:
            wavelength_um (list[float]): Wavelengths, µm, increasing, 2 to 64 of them. Example: [0.4, 0.55, 0.7].
            n (list[float] | None | Unset): Real part of the refractive index at each wavelength.
            k (list[float] | None | Unset): Imaginary part of the refractive index at each wavelength.
            albedo (list[float] | None | Unset): Lambertian albedo at each wavelength.
     """

    wavelength_um: list[float]
    n: list[float] | None | Unset = UNSET
    k: list[float] | None | Unset = UNSET
    albedo: list[float] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        wavelength_um = self.wavelength_um



        n: list[float] | None | Unset
        if isinstance(self.n, Unset):
            n = UNSET
        elif isinstance(self.n, list):
            n = self.n


        else:
            n = self.n

        k: list[float] | None | Unset
        if isinstance(self.k, Unset):
            k = UNSET
        elif isinstance(self.k, list):
            k = self.k


        else:
            k = self.k

        albedo: list[float] | None | Unset
        if isinstance(self.albedo, Unset):
            albedo = UNSET
        elif isinstance(self.albedo, list):
            albedo = self.albedo


        else:
            albedo = self.albedo


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "wavelength_um": wavelength_um,
        })
        if n is not UNSET:
            field_dict["n"] = n
        if k is not UNSET:
            field_dict["k"] = k
        if albedo is not UNSET:
            field_dict["albedo"] = albedo

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        wavelength_um = cast(list[float], d.pop("wavelength_um"))


        def _parse_n(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                n_type_0 = cast(list[float], data)

                return n_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        n = _parse_n(d.pop("n", UNSET))


        def _parse_k(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                k_type_0 = cast(list[float], data)

                return k_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        k = _parse_k(d.pop("k", UNSET))


        def _parse_albedo(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                albedo_type_0 = cast(list[float], data)

                return albedo_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        albedo = _parse_albedo(d.pop("albedo", UNSET))


        spectral_spec = cls(
            wavelength_um=wavelength_um,
            n=n,
            k=k,
            albedo=albedo,
        )

        return spectral_spec

