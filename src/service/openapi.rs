//! The OpenAPI document, generated from the handlers and the wire types by utoipa. The
//! committed `openapi/openapi.json` is this, printed by `glint openapi` (a test keeps them
//! equal).

use utoipa::openapi::security::{HttpAuthScheme, HttpBuilder, SecurityRequirement, SecurityScheme};
use utoipa::{Modify, OpenApi};

/// The document's fixed parts; the paths come from [`super::api_router`].
#[derive(OpenApi)]
#[openapi(
    info(
        title = "glint",
        description = "Photometric light curves of space objects over HTTP. Units are SI \
            (metres, seconds, W/m², W/sr) unless a field says otherwise. When the service runs \
            with `GLINT_API_TOKEN` set, every path but `/healthz` and `/readyz` needs \
            `Authorization: Bearer <token>`. Errors are `{\"error\": \"...\", \"field\": \"...\"}`.",
        license(name = "MIT", identifier = "MIT")
    ),
    tags(
        (name = "light curves", description = "Synchronous light-curve computation"),
        (name = "fits", description = "Material parameters fitted to measured BRDF samples; a request's parameters fitted to an observed light curve (a job)"),
        (name = "jobs", description = "Batch jobs, stored durably, that survive restarts"),
        (name = "scenes", description = "Built-in objects and example requests"),
        (name = "operations", description = "Health, readiness and metrics"),
    ),
    modifiers(&BearerAuth)
)]
pub struct ApiDoc;

struct BearerAuth;

impl Modify for BearerAuth {
    fn modify(&self, openapi: &mut utoipa::openapi::OpenApi) {
        let components = openapi.components.get_or_insert_with(Default::default);
        components.add_security_scheme(
            "bearer",
            SecurityScheme::Http(HttpBuilder::new().scheme(HttpAuthScheme::Bearer).build()),
        );
        // Optional: an empty requirement next to the bearer one means "or none", which is
        // the case when the service runs without a token.
        openapi.security = Some(vec![
            SecurityRequirement::new("bearer", Vec::<String>::new()),
            SecurityRequirement::default(),
        ]);
    }
}

/// The full document.
pub fn spec() -> utoipa::openapi::OpenApi {
    super::api_router().into_openapi()
}

/// The document as pretty JSON with a final newline, exactly as committed.
pub fn spec_json() -> String {
    let mut s = spec()
        .to_pretty_json()
        .unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"));
    s.push('\n');
    s
}
