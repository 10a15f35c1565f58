from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="Thumbnail")



@_attrs_define
class Thumbnail:
    """ One rendered image of the object as the observer sees it.

        Attributes:
            epoch (int): Index of the epoch in the request.
            t (float): Epoch time, seconds.
            size (int): Image width and height, pixels.
            metres_per_pixel (float): Scale of the image, metres per pixel (at the object).
            exposure_w_m2_sr (float): Radiance mapped to full white (8-bit 255), W/(m²·sr); one value for a whole sequence.
            png_base64 (str): The 8-bit PNG, base64-encoded.
     """

    epoch: int
    t: float
    size: int
    metres_per_pixel: float
    exposure_w_m2_sr: float
    png_base64: str
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        epoch = self.epoch

        t = self.t

        size = self.size

        metres_per_pixel = self.metres_per_pixel

        exposure_w_m2_sr = self.exposure_w_m2_sr

        png_base64 = self.png_base64


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "epoch": epoch,
            "t": t,
            "size": size,
            "metres_per_pixel": metres_per_pixel,
            "exposure_w_m2_sr": exposure_w_m2_sr,
            "png_base64": png_base64,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        epoch = d.pop("epoch")

        t = d.pop("t")

        size = d.pop("size")

        metres_per_pixel = d.pop("metres_per_pixel")

        exposure_w_m2_sr = d.pop("exposure_w_m2_sr")

        png_base64 = d.pop("png_base64")

        thumbnail = cls(
            epoch=epoch,
            t=t,
            size=size,
            metres_per_pixel=metres_per_pixel,
            exposure_w_m2_sr=exposure_w_m2_sr,
            png_base64=png_base64,
        )


        thumbnail.additional_properties = d
        return thumbnail

    @property
    def additional_keys(self) -> list[str]:
        return list(self.additional_properties.keys())

    def __getitem__(self, key: str) -> Any:
        return self.additional_properties[key]

    def __setitem__(self, key: str, value: Any) -> None:
        self.additional_properties[key] = value

    def __delitem__(self, key: str) -> None:
        del self.additional_properties[key]

    def __contains__(self, key: str) -> bool:
        return key in self.additional_properties
