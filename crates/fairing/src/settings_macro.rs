//! [`settings!`](crate::settings!): a method's settings struct declared with its defaults in
//! one place.

/// Declares a method's settings struct: each field with its doc comment (its meaning, the
/// first line of its row in the parameter table) and its default, as `name: Type = default`.
///
/// Expands to the struct with the conventions every catalogue entry follows (serde with
/// `default`, `deny_unknown_fields` and kebab-case names; a JSON Schema; `Debug`, `Clone`,
/// `PartialEq`), its `Default` from the given values and an empty
/// [`Settings`](crate::catalog::Settings) implementation. Derives go through the paths this
/// crate re-exports ([`serde`](crate::serde), [`schemars`](crate::schemars)), so a user crate
/// needs neither as a dependency. Other field attributes (`#[schemars(range(min = 1))]`, ...)
/// pass through. Settings that need their own [`validate`](crate::catalog::Settings::validate)
/// are written out by hand.
///
/// ```
/// fairing::settings! {
///     /// Laplacian smoothing.
///     pub struct LaplacianSettings {
///         /// How far towards the neighbours' midpoint per pass.
///         pub factor: f64 = 0.5,
///         /// Passes over the points.
///         pub max_passes: usize = 10,
///     }
/// }
/// let defaults = LaplacianSettings::default();
/// assert_eq!((defaults.factor, defaults.max_passes), (0.5, 10));
/// let given: LaplacianSettings = fairing::serde_json::from_str(r#"{"max-passes": 3}"#).unwrap();
/// assert_eq!((given.factor, given.max_passes), (0.5, 3));
/// assert!(fairing::serde_json::from_str::<LaplacianSettings>(r#"{"passes": 3}"#).is_err());
/// ```
#[macro_export]
macro_rules! settings {
    (
        $(#[$attr:meta])*
        $vis:vis struct $name:ident {
            $(
                $(#[$field_attr:meta])*
                $field_vis:vis $field:ident : $ty:ty = $default:expr
            ),* $(,)?
        }
    ) => {
        $(#[$attr])*
        #[derive(
            Debug,
            Clone,
            PartialEq,
            $crate::serde::Serialize,
            $crate::serde::Deserialize,
            $crate::schemars::JsonSchema
        )]
        #[serde(
            crate = "fairing::serde",
            default,
            deny_unknown_fields,
            rename_all = "kebab-case"
        )]
        #[schemars(crate = "fairing::schemars")]
        $vis struct $name {
            $(
                $(#[$field_attr])*
                $field_vis $field: $ty,
            )*
        }

        impl ::core::default::Default for $name {
            fn default() -> Self {
                $name {
                    $($field: $default,)*
                }
            }
        }

        impl $crate::catalog::Settings for $name {}
    };
}
