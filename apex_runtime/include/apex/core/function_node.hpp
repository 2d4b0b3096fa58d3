// A plain function or lambda as a node type: its arguments become inputs and
// its return value (or each element of a returned tuple) an output.
//   registerFunction(registry, "demo/Add", [](int a, int b) { return a + b; },
//                    "Adds two numbers", {"a", "b"}, {"sum"});
#pragma once

#include <tuple>
#include <type_traits>
#include <utility>

#include "apex/core/registry.hpp"

namespace apex {
namespace detail {

template <class F>
struct Signature : Signature<decltype(&F::operator())> {};
template <class R, class... A>
struct Signature<R (*)(A...)> {
  using Return = R;
  using Args = std::tuple<std::decay_t<A>...>;
};
template <class R, class... A>
struct Signature<R(A...)> : Signature<R (*)(A...)> {};
template <class C, class R, class... A>
struct Signature<R (C::*)(A...) const> : Signature<R (*)(A...)> {};
template <class C, class R, class... A>
struct Signature<R (C::*)(A...)> : Signature<R (*)(A...)> {};

template <class T>
struct IsTuple : std::false_type {};
template <class... T>
struct IsTuple<std::tuple<T...>> : std::true_type {};

/** The outputs as a tuple type: void → (), T → (T), tuple<T...> → (T...). */
template <class R>
using OutputsOf = std::conditional_t<std::is_void_v<R>, std::tuple<>, std::conditional_t<IsTuple<R>::value, R, std::tuple<R>>>;

template <class Tuple, class F, std::size_t... I>
void forEachType(F&& f, std::index_sequence<I...>) {
  (f(std::integral_constant<std::size_t, I>{}, static_cast<std::tuple_element_t<I, Tuple>*>(nullptr)), ...);
}

}  // namespace detail

template <class Fn>
class FunctionNode : public Node {
  using Sig = detail::Signature<std::decay_t<Fn>>;
  using Args = typename Sig::Args;
  using Outs = detail::OutputsOf<typename Sig::Return>;

 public:
  FunctionNode(Fn fn, std::vector<std::string> in, std::vector<std::string> out)
      : fn_(std::move(fn)), in_(std::move(in)), out_(std::move(out)) {}

  void process() override { call(std::make_index_sequence<std::tuple_size_v<Args>>{}); }

  static Manifest manifest(std::string desc, const std::vector<std::string>& in, const std::vector<std::string>& out) {
    Manifest m(std::move(desc));
    detail::forEachType<Args>([&](auto i, auto* t) { m.input<std::remove_pointer_t<decltype(t)>>(in[i]); },
                              std::make_index_sequence<std::tuple_size_v<Args>>{});
    detail::forEachType<Outs>([&](auto i, auto* t) { m.output<std::remove_pointer_t<decltype(t)>>(out[i]); },
                              std::make_index_sequence<std::tuple_size_v<Outs>>{});
    return m;
  }

 private:
  template <std::size_t... I>
  void call(std::index_sequence<I...>) {
    if constexpr (std::is_void_v<typename Sig::Return>) {
      fn_(*input<std::tuple_element_t<I, Args>>(in_[I])...);
    } else if constexpr (detail::IsTuple<typename Sig::Return>::value) {
      publishAll(fn_(*input<std::tuple_element_t<I, Args>>(in_[I])...), std::make_index_sequence<std::tuple_size_v<Outs>>{});
    } else {
      publish(out_[0], fn_(*input<std::tuple_element_t<I, Args>>(in_[I])...));
    }
  }
  template <std::size_t... I>
  void publishAll(Outs&& values, std::index_sequence<I...>) {
    (publish(out_[I], std::move(std::get<I>(values))), ...);
  }

  Fn fn_;
  std::vector<std::string> in_, out_;
};

/** @brief Registers a function or lambda as node type `id`. Input and output names
 *  default to in0, in1, ... and out0, out1, ...; their counts must match the signature. */
template <class Fn>
Status registerFunction(NodeRegistry& registry, const std::string& id, Fn fn, std::string description,
                        std::vector<std::string> inputs = {}, std::vector<std::string> outputs = {}) {
  using Sig = detail::Signature<std::decay_t<Fn>>;
  constexpr std::size_t kIn = std::tuple_size_v<typename Sig::Args>;
  constexpr std::size_t kOut = std::tuple_size_v<detail::OutputsOf<typename Sig::Return>>;
  if (inputs.empty())
    for (std::size_t i = 0; i < kIn; ++i) inputs.push_back("in" + std::to_string(i));
  if (outputs.empty())
    for (std::size_t i = 0; i < kOut; ++i) outputs.push_back("out" + std::to_string(i));
  if (inputs.size() != kIn || outputs.size() != kOut) {
    return Status::error("function node '" + id + "': the function has " + std::to_string(kIn) + " inputs and " +
                         std::to_string(kOut) + " outputs, but " + std::to_string(inputs.size()) + " and " +
                         std::to_string(outputs.size()) + " names were given");
  }
  Manifest m = FunctionNode<Fn>::manifest(std::move(description), inputs, outputs);
  return registry.add(id, std::move(m),
                      [fn, inputs, outputs] { return std::unique_ptr<Node>(new FunctionNode<Fn>(fn, inputs, outputs)); });
}

}  // namespace apex
