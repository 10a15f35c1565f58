from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.articulation_spec import ArticulationSpec
  from ..models.epoch_spec import EpochSpec
  from ..models.geometry_spec import GeometrySpec
  from ..models.illumination_spec import IlluminationSpec
  from ..models.object_spec import ObjectSpec
  from ..models.observation_spec import ObservationSpec
  from ..models.thumbnail_spec import ThumbnailSpec





T = TypeVar("T", bound="Request")



@_attrs_define
class Request:
    """ A light-curve request: one object, its epochs, and how it is lit.

        Attributes:
            object_ (ObjectSpec): The object: a triangle mesh and the materials its triangles use.
            epochs (list[EpochSpec] | None | Unset): The epochs to compute, in any order; results come back in the same
                order. Give
                either `epochs` or `geometry`, not both.
            geometry (GeometrySpec | None | Unset):
            illumination (IlluminationSpec | None | Unset):
            tolerance (float | None | Unset): Relative tolerance of the lit-and-visible area integration for partly shadowed
                faces (fraction of the epoch's unshadowed signal), where they are ray-sampled:
                faces clipped exactly (the usual case) are exact whatever it says. Default 1e-3. Example: 0.001.
            method (None | str | Unset): Integration method: `auto` (default), `silhouette`, `adaptive`, `centroid`,
                `convex` or `image`.
            image_size (int | None | Unset): `image` method only: pixels on a side of the orthographic view from the
                observer
                (it spans the object's bounding sphere), 8 to 4096. Default 256. Example: 256.
            image_samples (int | None | Unset): `image` method only: stratified samples per pixel side (samples² per pixel),
                1 to 16. Default 4. Example: 4.
            centroid_subdivisions (int | None | Unset): `centroid` method only: split every triangle into four this many
                times before
                casting one ray per direction at each centroid, 0 to 8. Default 0. Example: 0.
            thumbnails (None | ThumbnailSpec | Unset):
            observation (None | ObservationSpec | Unset):
            articulation (list[ArticulationSpec] | None | Unset): Articulated parts with explicit `epochs` (a `geometry`
                request gives them as
                `geometry.articulation`): the same list, an `angles` law's times on the epochs'
                own `t` scale.
     """

    object_: ObjectSpec
    epochs: list[EpochSpec] | None | Unset = UNSET
    geometry: GeometrySpec | None | Unset = UNSET
    illumination: IlluminationSpec | None | Unset = UNSET
    tolerance: float | None | Unset = UNSET
    method: None | str | Unset = UNSET
    image_size: int | None | Unset = UNSET
    image_samples: int | None | Unset = UNSET
    centroid_subdivisions: int | None | Unset = UNSET
    thumbnails: None | ThumbnailSpec | Unset = UNSET
    observation: None | ObservationSpec | Unset = UNSET
    articulation: list[ArticulationSpec] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.articulation_spec import ArticulationSpec # noqa: PLC0415
        from ..models.epoch_spec import EpochSpec # noqa: PLC0415
        from ..models.geometry_spec import GeometrySpec # noqa: PLC0415
        from ..models.illumination_spec import IlluminationSpec # noqa: PLC0415
        from ..models.object_spec import ObjectSpec # noqa: PLC0415
        from ..models.observation_spec import ObservationSpec # noqa: PLC0415
        from ..models.thumbnail_spec import ThumbnailSpec # noqa: PLC0415
        object_ = self.object_.to_dict()

        epochs: list[dict[str, Any]] | None | Unset
        if isinstance(self.epochs, Unset):
            epochs = UNSET
        elif isinstance(self.epochs, list):
            epochs = []
            for epochs_type_0_item_data in self.epochs:
                epochs_type_0_item = epochs_type_0_item_data.to_dict()
                epochs.append(epochs_type_0_item)


        else:
            epochs = self.epochs

        geometry: dict[str, Any] | None | Unset
        if isinstance(self.geometry, Unset):
            geometry = UNSET
        elif isinstance(self.geometry, GeometrySpec):
            geometry = self.geometry.to_dict()
        else:
            geometry = self.geometry

        illumination: dict[str, Any] | None | Unset
        if isinstance(self.illumination, Unset):
            illumination = UNSET
        elif isinstance(self.illumination, IlluminationSpec):
            illumination = self.illumination.to_dict()
        else:
            illumination = self.illumination

        tolerance: float | None | Unset
        if isinstance(self.tolerance, Unset):
            tolerance = UNSET
        else:
            tolerance = self.tolerance

        method: None | str | Unset
        if isinstance(self.method, Unset):
            method = UNSET
        else:
            method = self.method

        image_size: int | None | Unset
        if isinstance(self.image_size, Unset):
            image_size = UNSET
        else:
            image_size = self.image_size

        image_samples: int | None | Unset
        if isinstance(self.image_samples, Unset):
            image_samples = UNSET
        else:
            image_samples = self.image_samples

        centroid_subdivisions: int | None | Unset
        if isinstance(self.centroid_subdivisions, Unset):
            centroid_subdivisions = UNSET
        else:
            centroid_subdivisions = self.centroid_subdivisions

        thumbnails: dict[str, Any] | None | Unset
        if isinstance(self.thumbnails, Unset):
            thumbnails = UNSET
        elif isinstance(self.thumbnails, ThumbnailSpec):
            thumbnails = self.thumbnails.to_dict()
        else:
            thumbnails = self.thumbnails

        observation: dict[str, Any] | None | Unset
        if isinstance(self.observation, Unset):
            observation = UNSET
        elif isinstance(self.observation, ObservationSpec):
            observation = self.observation.to_dict()
        else:
            observation = self.observation

        articulation: list[dict[str, Any]] | None | Unset
        if isinstance(self.articulation, Unset):
            articulation = UNSET
        elif isinstance(self.articulation, list):
            articulation = []
            for articulation_type_0_item_data in self.articulation:
                articulation_type_0_item = articulation_type_0_item_data.to_dict()
                articulation.append(articulation_type_0_item)


        else:
            articulation = self.articulation


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "object": object_,
        })
        if epochs is not UNSET:
            field_dict["epochs"] = epochs
        if geometry is not UNSET:
            field_dict["geometry"] = geometry
        if illumination is not UNSET:
            field_dict["illumination"] = illumination
        if tolerance is not UNSET:
            field_dict["tolerance"] = tolerance
        if method is not UNSET:
            field_dict["method"] = method
        if image_size is not UNSET:
            field_dict["image_size"] = image_size
        if image_samples is not UNSET:
            field_dict["image_samples"] = image_samples
        if centroid_subdivisions is not UNSET:
            field_dict["centroid_subdivisions"] = centroid_subdivisions
        if thumbnails is not UNSET:
            field_dict["thumbnails"] = thumbnails
        if observation is not UNSET:
            field_dict["observation"] = observation
        if articulation is not UNSET:
            field_dict["articulation"] = articulation

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.articulation_spec import ArticulationSpec # noqa: PLC0415
        from ..models.epoch_spec import EpochSpec # noqa: PLC0415
        from ..models.geometry_spec import GeometrySpec # noqa: PLC0415
        from ..models.illumination_spec import IlluminationSpec # noqa: PLC0415
        from ..models.object_spec import ObjectSpec # noqa: PLC0415
        from ..models.observation_spec import ObservationSpec # noqa: PLC0415
        from ..models.thumbnail_spec import ThumbnailSpec # noqa: PLC0415
        d = dict(src_dict)
        object_ = ObjectSpec.from_dict(d.pop("object"))




        def _parse_epochs(data: object) -> list[EpochSpec] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                epochs_type_0 = []
                _epochs_type_0 = data
                for epochs_type_0_item_data in (_epochs_type_0):
                    epochs_type_0_item = EpochSpec.from_dict(epochs_type_0_item_data)



                    epochs_type_0.append(epochs_type_0_item)

                return epochs_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[EpochSpec] | None | Unset, data)

        epochs = _parse_epochs(d.pop("epochs", UNSET))


        def _parse_geometry(data: object) -> GeometrySpec | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                geometry_type_0 = GeometrySpec.from_dict(data)



                return geometry_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(GeometrySpec | None | Unset, data)

        geometry = _parse_geometry(d.pop("geometry", UNSET))


        def _parse_illumination(data: object) -> IlluminationSpec | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                illumination_type_0 = IlluminationSpec.from_dict(data)



                return illumination_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(IlluminationSpec | None | Unset, data)

        illumination = _parse_illumination(d.pop("illumination", UNSET))


        def _parse_tolerance(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        tolerance = _parse_tolerance(d.pop("tolerance", UNSET))


        def _parse_method(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        method = _parse_method(d.pop("method", UNSET))


        def _parse_image_size(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        image_size = _parse_image_size(d.pop("image_size", UNSET))


        def _parse_image_samples(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        image_samples = _parse_image_samples(d.pop("image_samples", UNSET))


        def _parse_centroid_subdivisions(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        centroid_subdivisions = _parse_centroid_subdivisions(d.pop("centroid_subdivisions", UNSET))


        def _parse_thumbnails(data: object) -> None | ThumbnailSpec | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                thumbnails_type_0 = ThumbnailSpec.from_dict(data)



                return thumbnails_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | ThumbnailSpec | Unset, data)

        thumbnails = _parse_thumbnails(d.pop("thumbnails", UNSET))


        def _parse_observation(data: object) -> None | ObservationSpec | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                observation_type_0 = ObservationSpec.from_dict(data)



                return observation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(None | ObservationSpec | Unset, data)

        observation = _parse_observation(d.pop("observation", UNSET))


        def _parse_articulation(data: object) -> list[ArticulationSpec] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                articulation_type_0 = []
                _articulation_type_0 = data
                for articulation_type_0_item_data in (_articulation_type_0):
                    articulation_type_0_item = ArticulationSpec.from_dict(articulation_type_0_item_data)



                    articulation_type_0.append(articulation_type_0_item)

                return articulation_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[ArticulationSpec] | None | Unset, data)

        articulation = _parse_articulation(d.pop("articulation", UNSET))


        request = cls(
            object_=object_,
            epochs=epochs,
            geometry=geometry,
            illumination=illumination,
            tolerance=tolerance,
            method=method,
            image_size=image_size,
            image_samples=image_samples,
            centroid_subdivisions=centroid_subdivisions,
            thumbnails=thumbnails,
            observation=observation,
            articulation=articulation,
        )

        return request

