""" Contains all the data models used in inputs/outputs """

from .angle_sample import AngleSample
from .articulation_spec import ArticulationSpec
from .attitude_spec import AttitudeSpec
from .brdf_fit import BrdfFit
from .brdf_fit_fixed import BrdfFitFixed
from .brdf_fit_material import BrdfFitMaterial
from .brdf_fit_parameters import BrdfFitParameters
from .brdf_fit_request import BrdfFitRequest
from .brdf_fit_request_fixed_type_0 import BrdfFitRequestFixedType0
from .brdf_fit_uncertainty import BrdfFitUncertainty
from .earth_orientation_spec import EarthOrientationSpec
from .epoch_result import EpochResult
from .epoch_spec import EpochSpec
from .error_body import ErrorBody
from .fitted_epoch import FittedEpoch
from .geometry_spec import GeometrySpec
from .health import Health
from .illumination_spec import IlluminationSpec
from .job_kind import JobKind
from .job_state import JobState
from .job_status import JobStatus
from .light_curve import LightCurve
from .lightcurve_fit import LightcurveFit
from .lightcurve_fit_parameters import LightcurveFitParameters
from .lightcurve_fit_request import LightcurveFitRequest
from .lightcurve_fit_request_start_type_0 import LightcurveFitRequestStartType0
from .lightcurve_fit_start import LightcurveFitStart
from .lightcurve_fit_uncertainty import LightcurveFitUncertainty
from .material_albedo import MaterialAlbedo
from .material_object import MaterialObject
from .mesh_spec import MeshSpec
from .object_spec import ObjectSpec
from .observation import Observation
from .observation_result import ObservationResult
from .observation_spec import ObservationSpec
from .orbit_spec import OrbitSpec
from .orbit_spec_omm_type_0 import OrbitSpecOmmType0
from .part_spec import PartSpec
from .quaternion_sample import QuaternionSample
from .request import Request
from .sample import Sample
from .scene_summary import SceneSummary
from .shadowing_spec import ShadowingSpec
from .site_spec import SiteSpec
from .solver_report import SolverReport
from .spectral_spec import SpectralSpec
from .summary import Summary
from .thumbnail import Thumbnail
from .thumbnail_spec import ThumbnailSpec
from .times_spec import TimesSpec
from .visible_only_spec import VisibleOnlySpec

__all__ = (
    "AngleSample",
    "ArticulationSpec",
    "AttitudeSpec",
    "BrdfFit",
    "BrdfFitFixed",
    "BrdfFitMaterial",
    "BrdfFitParameters",
    "BrdfFitRequest",
    "BrdfFitRequestFixedType0",
    "BrdfFitUncertainty",
    "EarthOrientationSpec",
    "EpochResult",
    "EpochSpec",
    "ErrorBody",
    "FittedEpoch",
    "GeometrySpec",
    "Health",
    "IlluminationSpec",
    "JobKind",
    "JobState",
    "JobStatus",
    "LightCurve",
    "LightcurveFit",
    "LightcurveFitParameters",
    "LightcurveFitRequest",
    "LightcurveFitRequestStartType0",
    "LightcurveFitStart",
    "LightcurveFitUncertainty",
    "MaterialAlbedo",
    "MaterialObject",
    "MeshSpec",
    "ObjectSpec",
    "Observation",
    "ObservationResult",
    "ObservationSpec",
    "OrbitSpec",
    "OrbitSpecOmmType0",
    "PartSpec",
    "QuaternionSample",
    "Request",
    "Sample",
    "SceneSummary",
    "ShadowingSpec",
    "SiteSpec",
    "SolverReport",
    "SpectralSpec",
    "Summary",
    "Thumbnail",
    "ThumbnailSpec",
    "TimesSpec",
    "VisibleOnlySpec",
)
