//! The one error of every handler: an HTTP status and the sentence the CLI would say.

use axum::Json;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use fuzzymotiv_pipeline::files::error::CliError;
use serde::de::DeserializeOwned;

/// An error answer: `{"error": message}` with `status`.
#[derive(Debug)]
pub struct ApiError {
    pub status: StatusCode,
    pub message: String,
}

impl ApiError {
    /// 400: the request asks for something that cannot be (the CLI's exit code 2).
    pub fn bad(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::BAD_REQUEST,
            message: message.into(),
        }
    }

    /// 404: no such run or room.
    pub fn not_found(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::NOT_FOUND,
            message: message.into(),
        }
    }

    /// 409: the request conflicts with what is there (a run not finished, a name taken).
    pub fn conflict(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::CONFLICT,
            message: message.into(),
        }
    }

    /// 503: the server cannot take more work now.
    pub fn busy(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::SERVICE_UNAVAILABLE,
            message: message.into(),
        }
    }
}

impl From<CliError> for ApiError {
    /// Bad input is the client's (400); anything else is the server's (500).
    fn from(e: CliError) -> Self {
        let status = if e.is_input() {
            StatusCode::BAD_REQUEST
        } else {
            StatusCode::INTERNAL_SERVER_ERROR
        };
        Self {
            status,
            message: e.to_string(),
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = Json(serde_json::json!({ "error": self.message }));
        (self.status, body).into_response()
    }
}

/// A request body read as JSON type `T`; a bad one is named as the CLI names a config field:
/// `request body: field `ga.population`: invalid type …`.
pub fn parse_body<T: DeserializeOwned>(body: &[u8]) -> Result<T, ApiError> {
    let de = &mut serde_json::Deserializer::from_slice(body);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        if path == "." || path.is_empty() {
            ApiError::bad(format!(
                "request body: not valid JSON of this request: {inner}"
            ))
        } else {
            ApiError::bad(format!("request body: field `{path}`: {inner}"))
        }
    })
}
