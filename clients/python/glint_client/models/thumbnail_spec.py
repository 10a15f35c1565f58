from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="ThumbnailSpec")



@_attrs_define
class ThumbnailSpec:
    """ Which epochs to render, and how. `every` and `epochs` may be combined (their union
    is rendered); with neither, about eight frames spread over the sequence.

        Attributes:
            size (int | None | Unset): Pixels on a side (square images), 8 to 2048. Default 128. Example: 128.
            every (int | None | Unset): Render every N-th epoch, starting with the first. Example: 10.
            epochs (list[int] | None | Unset): Indices of epochs to render (0-based, into `epochs`).
            samples (int | None | Unset): Stratified samples per pixel side (samples² per pixel), 1 to 16. Default 3.
            exposure (float | None | str | Unset):
     """

    size: int | None | Unset = UNSET
    every: int | None | Unset = UNSET
    epochs: list[int] | None | Unset = UNSET
    samples: int | None | Unset = UNSET
    exposure: float | None | str | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        size: int | None | Unset
        if isinstance(self.size, Unset):
            size = UNSET
        else:
            size = self.size

        every: int | None | Unset
        if isinstance(self.every, Unset):
            every = UNSET
        else:
            every = self.every

        epochs: list[int] | None | Unset
        if isinstance(self.epochs, Unset):
            epochs = UNSET
        elif isinstance(self.epochs, list):
            epochs = self.epochs


        else:
            epochs = self.epochs

        samples: int | None | Unset
        if isinstance(self.samples, Unset):
            samples = UNSET
        else:
            samples = self.samples

        exposure: float | None | str | Unset
        if isinstance(self.exposure, Unset):
            exposure = UNSET
        else:
            exposure = self.exposure


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if size is not UNSET:
            field_dict["size"] = size
        if every is not UNSET:
            field_dict["every"] = every
        if epochs is not UNSET:
            field_dict["epochs"] = epochs
        if samples is not UNSET:
            field_dict["samples"] = samples
        if exposure is not UNSET:
            field_dict["exposure"] = exposure

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        def _parse_size(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        size = _parse_size(d.pop("size", UNSET))


        def _parse_every(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        every = _parse_every(d.pop("every", UNSET))


        def _parse_epochs(data: object) -> list[int] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                epochs_type_0 = cast(list[int], data)

                return epochs_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[int] | None | Unset, data)

        epochs = _parse_epochs(d.pop("epochs", UNSET))


        def _parse_samples(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        samples = _parse_samples(d.pop("samples", UNSET))


        def _parse_exposure(data: object) -> float | None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | str | Unset, data)

        exposure = _parse_exposure(d.pop("exposure", UNSET))


        thumbnail_spec = cls(
            size=size,
            every=every,
            epochs=epochs,
            samples=samples,
            exposure=exposure,
        )

        return thumbnail_spec

