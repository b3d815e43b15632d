//! A config's or a room file's TOML read with its type errors in plain words: a field that takes
//! a whole number, a number or true/false says so ("expected a whole number from 2 to 1000000",
//! "expected a number (e.g. 0.5)", "expected true or false") where serde would name its Rust type
//! ("expected u64", "expected f64"). The words are produced by the visitors that read the
//! values, which know the field's path and so its range (the reader's `whole_number_range`, e.g.
//! the config's); nothing is rewritten afterwards.
//!
//! [`Plain`] wraps TOML's deserializer: it follows the path through tables, options and arrays,
//! and reads every bool, integer and float with a [`Typed`] visitor whose `expecting` is the
//! plain words; everything else (strings, enums, untagged values) goes to TOML unchanged, so
//! those messages and every line and column stay TOML's own. What a table's reader found wrong
//! with its keys (a field missing, a key it does not take) is kept as data beside TOML's error
//! ([`ReadError::fault`]), so that no one reads it back out of the message.

use std::cell::RefCell;
use std::fmt;
use std::rc::Rc;

use serde::de::{
    self, DeserializeSeed, Deserializer, IntoDeserializer, MapAccess, SeqAccess, Unexpected,
    Visitor,
};

/// What a table's reader found wrong with its keys, as data.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Fault {
    /// A field the table must have is not there: its name (the table is where TOML's span
    /// points).
    Missing(&'static str),
    /// A key the table does not take: its dotted path (`outline`, `ga.populaton`).
    Unknown(String),
}

/// A document that could not be read: TOML's error (its message and span) and, where a table's
/// reader found a key missing or unknown, that [`Fault`].
#[derive(Debug)]
pub(crate) struct ReadError {
    /// TOML's error: the message users see and where it is.
    pub(crate) toml: toml::de::Error,
    /// The key the error is about, where a table's reader said which.
    pub(crate) fault: Option<Fault>,
}

impl ReadError {
    /// The message, trimmed.
    pub(crate) fn message(&self) -> &str {
        self.toml.message().trim()
    }

    /// Where in the text the error is.
    pub(crate) fn span(&self) -> Option<std::ops::Range<usize>> {
        self.toml.span()
    }

    /// The field the error is in (see [`crate::params::field_at`]).
    pub(crate) fn field(&self, text: &str) -> String {
        match &self.fault {
            Some(Fault::Missing(name)) => crate::params::field_at(text, self.span(), Some(name)),
            Some(Fault::Unknown(key)) if self.span().is_none() => key.clone(),
            _ => crate::params::field_at(text, self.span(), None),
        }
    }
}

/// Reads a `T` from any deserializer `d` (a JSON record file's) with type errors in plain words,
/// a whole number said to be `whole_number_range(path)`.
pub(crate) fn deserialize<'de, T: de::Deserialize<'de>, D: Deserializer<'de>>(
    d: D,
    whole_number_range: fn(&str) -> String,
) -> Result<T, D::Error> {
    let path = Path {
        keys: String::new(),
        whole_number_range,
        fault: Rc::new(RefCell::new(None)),
    };
    T::deserialize(Plain { inner: d, path })
}

/// Reads `text` as a `T` (a config, a room), type errors in plain words; a whole number is
/// said to be `whole_number_range(path)`, e.g. "from 2 to 1000000" for `ga.population`.
pub(crate) fn from_str<'de, T: de::Deserialize<'de>>(
    text: &'de str,
    whole_number_range: fn(&str) -> String,
) -> Result<T, ReadError> {
    let inner = toml::Deserializer::parse(text).map_err(|toml| ReadError { toml, fault: None })?;
    let fault = Rc::new(RefCell::new(None));
    let path = Path {
        keys: String::new(),
        whole_number_range,
        fault: Rc::clone(&fault),
    };
    T::deserialize(Plain { inner, path }).map_err(|toml| ReadError {
        toml,
        fault: fault.take(),
    })
}

/// Where a value is: its dotted keys (empty at the document), and how the reader words the
/// range of a whole number there.
#[derive(Clone)]
struct Path {
    keys: String,
    whole_number_range: fn(&str) -> String,
    /// The first [`Fault`] a table's reader found (shared by every path of the document).
    fault: Rc<RefCell<Option<Fault>>>,
}

impl Path {
    /// The path of the entry `key` of the table here.
    fn child(&self, key: &str) -> Path {
        let keys = if self.keys.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.keys)
        };
        Path {
            keys,
            ..self.clone()
        }
    }

    /// Keeps `fault` as the document's, unless one was found first (deeper in).
    fn found(&self, fault: Fault) {
        self.fault.borrow_mut().get_or_insert(fault);
    }
}

/// A deserializer at `path`.
struct Plain<D> {
    inner: D,
    path: Path,
}

/// What a scalar field takes, in the words of its messages.
#[derive(Clone, Copy)]
enum Kind {
    /// true or false.
    Bool,
    /// A whole number from 0 to the maximum of its type.
    Unsigned(u64),
    /// A whole number in the range of its type.
    Signed(i64, i64),
    /// Any number.
    Number,
}

/// Visit methods handed to the field's own visitor as they are.
macro_rules! delegate {
    ($($method:ident($t:ty))*) => {$(
        fn $method<E: de::Error>(self, v: $t) -> Result<V::Value, E> {
            self.inner.$method(v)
        }
    )*};
}

/// Scalar methods, read with a [`Typed`] visitor of their kind.
macro_rules! typed {
    ($($method:ident => $kind:expr),* $(,)?) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
            let kind = $kind;
            self.inner.deserialize_any(Typed { inner: visitor, kind, path: self.path })
        }
    )*};
}

/// Methods handed to TOML's deserializer as they are.
macro_rules! forward {
    ($($method:ident)*) => {$(
        fn $method<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
            self.inner.$method(visitor)
        }
    )*};
}

impl<'de, D: Deserializer<'de>> Deserializer<'de> for Plain<D> {
    type Error = D::Error;

    /// Whatever comes (a value of a type's own visitor, e.g. a weight or a table): a table or
    /// an array in it is read with the path still followed.
    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        let path = self.path;
        self.inner.deserialize_any(Nested {
            inner: visitor,
            path,
        })
    }

    typed! {
        deserialize_bool => Kind::Bool,
        deserialize_u8 => Kind::Unsigned(u8::MAX.into()),
        deserialize_u16 => Kind::Unsigned(u16::MAX.into()),
        deserialize_u32 => Kind::Unsigned(u32::MAX.into()),
        deserialize_u64 => Kind::Unsigned(u64::MAX),
        deserialize_i8 => Kind::Signed(i8::MIN.into(), i8::MAX.into()),
        deserialize_i16 => Kind::Signed(i16::MIN.into(), i16::MAX.into()),
        deserialize_i32 => Kind::Signed(i32::MIN.into(), i32::MAX.into()),
        deserialize_i64 => Kind::Signed(i64::MIN, i64::MAX),
        deserialize_f32 => Kind::Number,
        deserialize_f64 => Kind::Number,
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        let path = self.path;
        self.inner.deserialize_option(Nested {
            inner: visitor,
            path,
        })
    }

    fn deserialize_seq<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        let path = self.path;
        self.inner.deserialize_seq(Nested {
            inner: visitor,
            path,
        })
    }

    fn deserialize_map<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, Self::Error> {
        let path = self.path;
        self.inner.deserialize_map(Nested {
            inner: visitor,
            path,
        })
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        let path = self.path;
        self.inner.deserialize_struct(
            name,
            fields,
            Nested {
                inner: visitor,
                path,
            },
        )
    }

    fn deserialize_unit_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.inner.deserialize_unit_struct(name, visitor)
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.inner.deserialize_newtype_struct(name, visitor)
    }

    fn deserialize_tuple<V: Visitor<'de>>(
        self,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.inner.deserialize_tuple(len, visitor)
    }

    fn deserialize_tuple_struct<V: Visitor<'de>>(
        self,
        name: &'static str,
        len: usize,
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.inner.deserialize_tuple_struct(name, len, visitor)
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, Self::Error> {
        self.inner.deserialize_enum(name, variants, visitor)
    }

    forward! {
        deserialize_i128 deserialize_u128 deserialize_char deserialize_str deserialize_string
        deserialize_bytes deserialize_byte_buf deserialize_unit deserialize_identifier
        deserialize_ignored_any
    }
}

/// A scalar's visitor: accepts what `kind` takes, hands it to the field's own visitor, and
/// says what it expects in plain words.
struct Typed<V> {
    inner: V,
    kind: Kind,
    path: Path,
}

impl<'de, V: Visitor<'de>> Visitor<'de> for Typed<V> {
    type Value = V::Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            Kind::Bool => f.write_str("true or false"),
            Kind::Number => f.write_str("a number (e.g. 0.5)"),
            Kind::Unsigned(_) | Kind::Signed(..) => {
                write!(
                    f,
                    "a whole number {}",
                    (self.path.whole_number_range)(&self.path.keys)
                )
            }
        }
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<V::Value, E> {
        match self.kind {
            Kind::Bool => self.inner.visit_bool(v),
            _ => Err(E::invalid_type(Unexpected::Bool(v), &self)),
        }
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<V::Value, E> {
        match self.kind {
            Kind::Number => self.inner.visit_i64(v),
            Kind::Unsigned(max) if v >= 0 && v as u64 <= max => self.inner.visit_u64(v as u64),
            Kind::Signed(min, max) if (min..=max).contains(&v) => self.inner.visit_i64(v),
            Kind::Unsigned(_) | Kind::Signed(..) => {
                Err(E::invalid_value(Unexpected::Signed(v), &self))
            }
            Kind::Bool => Err(E::invalid_type(Unexpected::Signed(v), &self)),
        }
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<V::Value, E> {
        match self.kind {
            Kind::Number => self.inner.visit_u64(v),
            Kind::Unsigned(max) if v <= max => self.inner.visit_u64(v),
            Kind::Signed(_, max) if v <= max as u64 => self.inner.visit_i64(v as i64),
            Kind::Unsigned(_) | Kind::Signed(..) => {
                Err(E::invalid_value(Unexpected::Unsigned(v), &self))
            }
            Kind::Bool => Err(E::invalid_type(Unexpected::Unsigned(v), &self)),
        }
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<V::Value, E> {
        match self.kind {
            Kind::Number => self.inner.visit_f64(v),
            _ => Err(E::invalid_type(Unexpected::Float(v), &self)),
        }
    }
}

/// The visitor of a table, an array, an option or any value: the field's own (its words are
/// the field's, every value goes to it), with the path handed down to what it contains.
struct Nested<V> {
    inner: V,
    path: Path,
}

impl<'de, V: Visitor<'de>> Visitor<'de> for Nested<V> {
    type Value = V::Value;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.inner.expecting(f)
    }

    fn visit_none<E: de::Error>(self) -> Result<V::Value, E> {
        self.inner.visit_none()
    }

    delegate! {
        visit_bool(bool) visit_i64(i64) visit_u64(u64) visit_i128(i128) visit_u128(u128)
        visit_f64(f64) visit_char(char) visit_str(&str) visit_borrowed_str(&'de str)
        visit_string(String) visit_bytes(&[u8]) visit_borrowed_bytes(&'de [u8])
        visit_byte_buf(Vec<u8>)
    }

    fn visit_unit<E: de::Error>(self) -> Result<V::Value, E> {
        self.inner.visit_unit()
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, d: D) -> Result<V::Value, D::Error> {
        self.inner.visit_newtype_struct(d)
    }

    fn visit_enum<A: de::EnumAccess<'de>>(self, data: A) -> Result<V::Value, A::Error> {
        self.inner.visit_enum(data)
    }

    fn visit_some<D: Deserializer<'de>>(self, d: D) -> Result<V::Value, D::Error> {
        let path = self.path;
        self.inner.visit_some(Plain { inner: d, path })
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<V::Value, A::Error> {
        let path = self.path;
        self.inner.visit_seq(Nested { inner: seq, path })
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<V::Value, A::Error> {
        let path = self.path.clone();
        (self.inner)
            .visit_map(Table {
                inner: map,
                path: self.path,
                key: String::new(),
            })
            .map_err(|caught| match caught {
                Caught::Inner(e) => e,
                Caught::Missing(name) => {
                    path.found(Fault::Missing(name));
                    de::Error::missing_field(name)
                }
                Caught::Custom(message) => de::Error::custom(message),
            })
    }
}

impl<'de, A: SeqAccess<'de>> SeqAccess<'de> for Nested<A> {
    type Error = A::Error;

    fn next_element_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<Option<T::Value>, A::Error> {
        let path = self.path.clone();
        self.inner.next_element_seed(At { inner: seed, path })
    }

    fn size_hint(&self) -> Option<usize> {
        self.inner.size_hint()
    }
}

/// A table's entries, each value at the path of its key.
struct Table<A> {
    inner: A,
    path: Path,
    key: String,
}

/// The error a table's own reader (a struct's visitor) returns: an error of what it read, passed
/// on as it is, or one it raised itself, a missing field kept as data.
#[derive(Debug)]
enum Caught<E> {
    /// An error of a key or a value, from TOML or a visitor below.
    Inner(E),
    /// The reader's "missing field".
    Missing(&'static str),
    /// Any other error the reader raised (in serde's words).
    Custom(String),
}

impl<E: fmt::Display> fmt::Display for Caught<E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Caught::Inner(e) => e.fmt(f),
            Caught::Missing(name) => write!(f, "missing field `{name}`"),
            Caught::Custom(message) => f.write_str(message),
        }
    }
}

impl<E: fmt::Debug + fmt::Display> std::error::Error for Caught<E> {}

impl<E: de::Error> de::Error for Caught<E> {
    fn custom<T: fmt::Display>(message: T) -> Self {
        Caught::Custom(message.to_string())
    }

    fn missing_field(field: &'static str) -> Self {
        Caught::Missing(field)
    }
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for Table<A> {
    type Error = Caught<A::Error>;

    fn next_key_seed<K: DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, Self::Error> {
        (self.inner)
            .next_key_seed(Key {
                inner: seed,
                key: &mut self.key,
                path: &self.path,
            })
            .map_err(Caught::Inner)
    }

    fn next_value_seed<T: DeserializeSeed<'de>>(
        &mut self,
        seed: T,
    ) -> Result<T::Value, Self::Error> {
        let path = self.path.child(&self.key);
        (self.inner)
            .next_value_seed(At { inner: seed, path })
            .map_err(Caught::Inner)
    }

    fn size_hint(&self) -> Option<usize> {
        self.inner.size_hint()
    }
}

/// A key, kept for the path of its value; a key the table's reader refuses is kept as
/// [`Fault::Unknown`].
struct Key<'k, K> {
    inner: K,
    key: &'k mut String,
    path: &'k Path,
}

impl<'de, K: DeserializeSeed<'de>> DeserializeSeed<'de> for Key<'_, K> {
    type Value = K::Value;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<K::Value, D::Error> {
        let key = <String as de::Deserialize>::deserialize(d)?;
        self.key.clone_from(&key);
        let path = self.path;
        (self.inner)
            .deserialize(key.clone().into_deserializer())
            .inspect_err(|_| path.found(Fault::Unknown(path.child(&key).keys)))
    }
}

/// A value read at `path`.
struct At<T> {
    inner: T,
    path: Path,
}

impl<'de, T: DeserializeSeed<'de>> DeserializeSeed<'de> for At<T> {
    type Value = T::Value;

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<T::Value, D::Error> {
        self.inner.deserialize(Plain {
            inner: d,
            path: self.path,
        })
    }
}

#[cfg(test)]
mod tests {
    use crate::experiment::config::{RawConfig, whole_number_range};

    /// The reason of the error of `text` read as a config.
    fn reason(text: &str) -> String {
        RawConfig::parse(text, "c.toml", &[]).unwrap_err().reason
    }

    #[test]
    fn type_errors_say_what_the_field_takes_in_plain_words() {
        assert_eq!(
            reason("[ga]\npopulation = 1.5\n"),
            "invalid type: floating point `1.5`, expected a whole number from 2 to 1000000 \
             (line 2, column 14)"
        );
        assert_eq!(
            reason("[trial]\nsteps = -3\n"),
            "invalid value: integer `-3`, expected a whole number from 1 to 10000000 \
             (line 2, column 9)"
        );
        assert_eq!(
            reason("[fuzzy]\npeaks = [0, \"a\", 1]\n"),
            "invalid type: string \"a\", expected a number (e.g. 0.5) (line 2, column 13)"
        );
        assert_eq!(
            reason("[trial]\nend_at_home = 1\n"),
            "invalid type: integer `1`, expected true or false (line 2, column 15)"
        );
        assert_eq!(
            reason("seed = \"one\"\n"),
            "invalid type: string \"one\", expected a whole number from 0 to 9007199254740991 \
             (2^53 − 1) (line 1, column 8)"
        );
    }

    /// Everything else is TOML's and serde's own: an unknown key, a word for an enum, a table
    /// where a number belongs; and good values read as they are.
    #[test]
    fn other_errors_and_good_values_are_read_as_toml_reads_them() {
        assert!(
            reason("[ga]\npopulaton = 3\n")
                .starts_with("unknown field `populaton`, expected one of"),
            "{}",
            reason("[ga]\npopulaton = 3\n")
        );
        assert!(reason("[fitness]\nhoming = \"far\"\n").starts_with("unknown variant `far`"));
        let raw = RawConfig::parse(
            "seed = 7\n[ga]\npopulation = 12\n[trial]\nend_at_home = false\n",
            "c",
            &[],
        )
        .unwrap();
        assert_eq!((raw.seed, raw.ga.population), (7, 12));
        assert!(!raw.trial.end_at_home);
    }

    /// A type that reads itself with `deserialize_any` (a number or a table, as a motivation
    /// may be written): the numbers in its table still say what they take.
    #[test]
    fn a_table_read_through_deserialize_any_keeps_the_plain_words() {
        use serde::Deserialize;
        use serde::de::{self, Deserializer, MapAccess, Visitor};
        #[derive(Deserialize)]
        struct Table {
            weight: f64,
        }
        struct Either(f64);
        impl<'de> Deserialize<'de> for Either {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                struct V;
                impl<'de> Visitor<'de> for V {
                    type Value = Either;
                    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                        f.write_str("a weight or a table")
                    }
                    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Either, E> {
                        Ok(Either(v))
                    }
                    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Either, A::Error> {
                        let t = Table::deserialize(de::value::MapAccessDeserializer::new(map))?;
                        Ok(Either(t.weight))
                    }
                }
                d.deserialize_any(V)
            }
        }
        #[derive(Deserialize)]
        struct Doc {
            x: Either,
        }
        let e = super::from_str::<Doc>("x = { weight = \"a\" }\n", whole_number_range)
            .err()
            .unwrap();
        assert_eq!(
            e.message(),
            "invalid type: string \"a\", expected a number (e.g. 0.5)"
        );
        let e = super::from_str::<Doc>("x = true\n", whole_number_range)
            .err()
            .unwrap();
        assert_eq!(
            e.message(),
            "invalid type: boolean `true`, expected a weight or a table"
        );
        let read = |text| {
            super::from_str::<Doc>(text, whole_number_range)
                .ok()
                .unwrap()
                .x
                .0
        };
        assert_eq!(
            (read("x = 0.5"), read("x = { weight = 0.25 }")),
            (0.5, 0.25)
        );
    }

    /// What a table's reader finds wrong with its keys is kept as data beside TOML's error: a
    /// missing field by its name (the config's field then under its table), a key not taken
    /// by its path; a room's key in a config gets the room-file hint, the same key deeper in
    /// does not.
    #[test]
    fn a_missing_or_unknown_key_is_kept_as_data() {
        use super::Fault;
        #[derive(serde::Deserialize)]
        #[allow(dead_code)]
        struct Home {
            x: f64,
            y: f64,
        }
        #[derive(serde::Deserialize)]
        #[allow(dead_code)]
        struct Room {
            name: String,
            home: Home,
        }
        let text = "name = \"r\"\nhome = { x = 1 }\n";
        let e = super::from_str::<Room>(text, |_| "≥ 0".into())
            .err()
            .unwrap();
        assert_eq!(e.fault, Some(Fault::Missing("y")));
        assert_eq!(e.field(text), "home.y");
        let e = super::from_str::<RawConfig>("[ga]\npopulaton = 3\n", whole_number_range)
            .err()
            .unwrap();
        assert_eq!(e.fault, Some(Fault::Unknown("ga.populaton".into())));
        let hint = "This looks like a room file";
        assert!(reason("outline = [[0, 0]]\n").contains(hint));
        assert!(
            !reason("[ga]\noutline = 3\n").contains(hint),
            "{}",
            reason("[ga]\noutline = 3\n")
        );
    }
}
