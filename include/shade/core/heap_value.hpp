#pragma once
// shade::detail::heap_value: one value kept on the heap with the semantics of a plain member
// (copies copy it, moves take it), for the large tables a few models build only for some
// parameters, so that an object without the table stays small.

namespace shade::detail {

/// An optional V held on the heap: empty by default; a copy holds a copy of the value (or is
/// empty), a move takes the pointer and leaves the source empty. No <memory> (the headers'
/// preprocessed-size budget): a plain owning pointer with the five special members.
template <class V>
class heap_value {
public:
    heap_value() = default;
    heap_value(const heap_value& other) : value_(other.value_ != nullptr ? new V(*other.value_) : nullptr) {}
    heap_value(heap_value&& other) noexcept : value_(other.value_) { other.value_ = nullptr; }
    heap_value& operator=(heap_value other) noexcept {
        V* const mine = value_;
        value_ = other.value_;
        other.value_ = mine;
        return *this;
    }
    ~heap_value() { delete value_; }

    /// Replaces the value (or the emptiness) with V(args...); returns it.
    template <class... Args>
    V& emplace(Args&&... args) {
        V* const made = new V(static_cast<Args&&>(args)...);
        delete value_;
        value_ = made;
        return *value_;
    }

    /// The value, or nullptr when empty.
    [[nodiscard]] const V* get() const noexcept { return value_; }
    /// The value, or nullptr when empty.
    [[nodiscard]] V* get() noexcept { return value_; }
    /// Whether a value is held.
    [[nodiscard]] bool has_value() const noexcept { return value_ != nullptr; }
    /// The value (has_value() required).
    [[nodiscard]] const V& operator*() const noexcept { return *value_; }
    /// The value (has_value() required).
    [[nodiscard]] V& operator*() noexcept { return *value_; }
    /// The value's members (has_value() required).
    [[nodiscard]] const V* operator->() const noexcept { return value_; }
    /// The value's members (has_value() required).
    [[nodiscard]] V* operator->() noexcept { return value_; }

private:
    V* value_ = nullptr;
};

} // namespace shade::detail
