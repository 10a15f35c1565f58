//! `/v1/scenes…`: the built-in objects and their example requests.

use super::body_response;
use crate::scene::Request;
use crate::service::errors::{ApiError, ErrorBody};
use crate::service::scenes::{self, SceneSummary};
use axum::extract::Path;
use axum::response::Response as HttpResponse;
use axum::Json;

/// The built-in objects and their example requests.
#[utoipa::path(
    get, path = "/v1/scenes", tag = "scenes",
    responses((status = 200, description = "Built-in objects and example requests", body = Vec<SceneSummary>))
)]
pub async fn list_scenes() -> Json<Vec<SceneSummary>> {
    Json(scenes::summaries().to_vec())
}

/// An example request, ready to send to `POST /v1/lightcurves` or `POST /v1/jobs`.
#[utoipa::path(
    get, path = "/v1/scenes/{name}", tag = "scenes",
    params(("name" = String, Path, description = "Scene name, e.g. `box-wing`")),
    responses(
        (status = 200, description = "The example request", body = Request),
        (status = 404, description = "No such scene", body = ErrorBody),
    )
)]
pub async fn get_scene(Path(name): Path<String>) -> Result<HttpResponse, ApiError> {
    scenes::example(&name)
        .map(|text| body_response(text.as_bytes().to_vec(), false))
        .ok_or_else(|| {
            ApiError::not_found(format!("no scene `{name}`; GET /v1/scenes lists them"))
                .with_field("name")
        })
}
