//! Rooms in the lab: the built-in ones, and rooms drawn or uploaded in the page, checked with
//! the library's room-file checks (the texts of `fuzzymotiv rooms --check`, naming the drawn
//! room instead of a file) and kept as room files under `DIR/rooms/`.

use std::path::Path;

use fuzzymotiv::simulation::{BUILTIN_ROOMS, Room};
use fuzzymotiv_pipeline::files::guard::{FilesState, check_files, write_files};
use serde::{Deserialize, Serialize};

use crate::errors::ApiError;
use crate::limits::{MAX_ROOM_VERTICES, MAX_SAVED_ROOMS};

/// The folder of the lab's rooms, under its directory.
pub const ROOM_DIR: &str = "rooms";

/// Whether `name` may name a room file of the lab: 1 to 40 letters, digits, `-` or `_`.
pub fn valid_room_name(name: &str) -> bool {
    (1..=40).contains(&name.len())
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// A room sent by the page: drawn (`room`, the room-file keys as JSON) or uploaded (`toml`,
/// a room file's text); `save` also writes it to `DIR/rooms/NAME.toml`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomRequest {
    #[serde(default)]
    pub room: Option<serde_json::Value>,
    #[serde(default)]
    pub toml: Option<String>,
    #[serde(default)]
    pub save: bool,
}

/// A room as the page draws it.
#[derive(Debug, Serialize)]
pub struct RoomView {
    /// The entry a run's settings name it by (`H`, or `U.toml`).
    pub entry: String,
    pub builtin: bool,
    /// A room of the config the lab started on (`--config`).
    pub config: bool,
    pub room: Room,
}

/// A room that failed its checks: the message, and the field it names (`outline`,
/// `obstacles[1].outline`, `home.x`, …) so that the page can mark the vertex.
#[derive(Debug, Serialize)]
pub struct RoomProblem {
    pub error: String,
    pub field: String,
}

/// The room's text as a room file, and where it came from (for messages).
fn room_text(req: &RoomRequest) -> Result<(String, String), ApiError> {
    match (&req.room, &req.toml) {
        (Some(room), None) => {
            let name = room.get("name").and_then(|n| n.as_str()).unwrap_or("");
            let bad = |e: &dyn std::fmt::Display| {
                ApiError::bad(format!("drawn room `{name}`: cannot be a room file: {e}"))
            };
            let value = toml::Value::try_from(room).map_err(|e| bad(&e))?;
            let toml::Value::Table(table) = value else {
                return Err(bad(&"not a table of room-file keys"));
            };
            Ok((room_file(table), format!("drawn room `{name}`")))
        }
        (None, Some(text)) => Ok((text.clone(), "uploaded room file".to_string())),
        _ => Err(ApiError::bad(
            "request body: give either `room` (a drawn room) or `toml` (a room file's text)",
        )),
    }
}

/// A room file's text as the shipped rooms write it: plain keys, then the discs and the home
/// as inline tables (`home = { … }`, `goal = { x, y, radius }`), then the obstacles and
/// waypoints as arrays of tables (`[[waypoints]]`).
fn room_file(table: toml::Table) -> String {
    let (mut plain, mut inline, mut sections) =
        (toml::Table::new(), String::new(), toml::Table::new());
    for (k, v) in table {
        match v {
            toml::Value::Table(_) => inline += &format!("{k} = {v}\n"),
            toml::Value::Array(a) if a.iter().any(toml::Value::is_table) => {
                sections.insert(k, toml::Value::Array(a));
            }
            v => {
                plain.insert(k, v);
            }
        }
    }
    let mut text = toml::to_string(&plain).unwrap_or_default();
    text += &inline;
    if !sections.is_empty() {
        text += "\n";
        text += &toml::to_string(&sections).unwrap_or_default();
    }
    text
}

/// Checks a room; `Err(Ok(problem))` for a room the checks refuse (with its field).
pub fn check(req: &RoomRequest) -> Result<Result<(Room, String), RoomProblem>, ApiError> {
    let (text, source) = room_text(req)?;
    if let Err(e) = toml::from_str::<toml::Table>(&text) {
        return Ok(Err(RoomProblem {
            error: format!("{source}: not valid TOML: {}", e.message().trim()),
            field: String::new(),
        }));
    }
    match Room::from_toml_str(&text, &source) {
        Err(e) => Ok(Err(RoomProblem {
            error: e.to_string(),
            field: e.field.clone(),
        })),
        Ok(room) if vertex_count(&room) > MAX_ROOM_VERTICES => Ok(Err(RoomProblem {
            error: format!(
                "{source}: field `outline`: {} vertices; the lab takes rooms of at most {MAX_ROOM_VERTICES}",
                vertex_count(&room)
            ),
            field: "outline".into(),
        })),
        Ok(room) if !valid_room_name(&room.name) || Room::builtin(&room.name).is_some() => {
            Ok(Err(RoomProblem {
                error: format!(
                    "{source}: field `name`: `{}` cannot name a room of the lab: use 1 to 40 letters, digits, - or _, and not a built-in room's name",
                    room.name
                ),
                field: "name".into(),
            }))
        }
        Ok(room) => Ok(Ok((room, text))),
    }
}

fn vertex_count(room: &Room) -> usize {
    room.outline.len() + room.obstacles.iter().map(Vec::len).sum::<usize>()
}

/// Writes a checked room to `DIR/rooms/NAME.toml` through the output guard: the same room
/// again is left alone, another room of that name is kept (409).
pub fn save(dir: &Path, room: &Room, text: &str) -> Result<String, ApiError> {
    let folder = dir.join(ROOM_DIR);
    let entry = format!("{}.toml", room.name);
    let path = folder.join(&entry);
    if !path.exists() && saved_rooms(dir).len() >= MAX_SAVED_ROOMS {
        return Err(ApiError::busy(format!(
            "the lab keeps at most {MAX_SAVED_ROOMS} rooms; remove some from {}",
            folder.display()
        )));
    }
    std::fs::create_dir_all(&folder)
        .map_err(|e| ApiError::from(fuzzymotiv_pipeline::files::guard::io_err(&folder, e)))?;
    let files = vec![(path, text.as_bytes().to_vec())];
    match check_files(&files, "room name", false) {
        Ok(FilesState::Same) => Ok(entry),
        Ok(FilesState::Write) => {
            write_files(&files)?;
            Ok(entry)
        }
        Err(e) => Err(ApiError::conflict(format!(
            "{e} (choose another room name)"
        ))),
    }
}

/// The rooms saved in the lab (entry names), sorted.
fn saved_rooms(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir.join(ROOM_DIR))
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .filter(|n| n.strip_suffix(".toml").is_some_and(valid_room_name))
        .collect();
    names.sort();
    names
}

/// Every room a run may use: the built-in ones, then the lab's saved rooms that still pass
/// the checks.
pub fn list(dir: &Path) -> Vec<RoomView> {
    let builtin = BUILTIN_ROOMS.iter().filter_map(|&name| {
        Room::builtin(name).map(|room| RoomView {
            entry: name.to_string(),
            builtin: true,
            config: false,
            room,
        })
    });
    let saved = saved_rooms(dir).into_iter().filter_map(|entry| {
        let path = dir.join(ROOM_DIR).join(&entry);
        let text = std::fs::read_to_string(&path).ok()?;
        let room = Room::from_toml_str(&text, &path.display().to_string()).ok()?;
        Some(RoomView {
            entry,
            builtin: false,
            config: false,
            room,
        })
    });
    builtin.chain(saved).collect()
}
