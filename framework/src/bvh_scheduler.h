// The BVH build's threads (framework/src/bvh.cpp): the shared work list, fork_join, and
// the node lists that subtrees built by other threads are written to.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "raylab/bvh.h"

namespace raylab::bvh_build {

// The 8-wide nodes of one subtree built by one thread, in depth-first order, except the
// children handed to other threads: each is a Fixup, child slot of node, whose subtree
// belongs before nodes[at] in depth-first order. join() splices them in there
struct Output {
    struct Fixup {
        std::uint32_t node;
        int slot;
        Output* subtree;
        std::uint32_t at;
    };
    std::vector<Bvh::Node> nodes;
    std::vector<Fixup> fixups;
    std::vector<std::uint32_t> index;  // of each node in the finished tree
};

// The work list the build threads share: jobs waiting for a thread, how many jobs are
// still unfinished (waiting or running) and how many threads wait for one
class Scheduler {
  public:
    void push(std::function<void()> job) {
        const std::lock_guard<std::mutex> lock(mutex_);
        waiting_.push_back(std::move(job));
        ++unfinished_;
        wake_.notify_one();
    }
    // Runs jobs, oldest (largest) first, until all are done
    void work() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(mutex_);
                ++idle_;
                wake_.wait(lock, [&] { return !waiting_.empty() || unfinished_ == 0; });
                --idle_;
                if (waiting_.empty()) return;
                job = std::move(waiting_.front());
                waiting_.pop_front();
            }
            // A failed job (out of memory) is reported after all threads are done
            std::exception_ptr failed;
            try {
                job();
            } catch (...) {
                failed = std::current_exception();
            }
            const std::lock_guard<std::mutex> lock(mutex_);
            if (failed && !error_) error_ = failed;
            if (--unfinished_ == 0) wake_.notify_all();
        }
    }
    std::exception_ptr error() const { return error_; }
    // A hint only: whether a thread waits for work now
    bool has_idle() const { return idle_.load(std::memory_order_relaxed) > 0; }
    // An output for a subtree; its address stays valid until the scheduler goes
    Output* new_output() {
        const std::lock_guard<std::mutex> lock(mutex_);
        outputs_.emplace_back();
        return &outputs_.back();
    }
    std::deque<Output>& outputs() { return outputs_; }

  private:
    std::mutex mutex_;
    std::condition_variable wake_;
    std::deque<std::function<void()>> waiting_;
    std::deque<Output> outputs_;
    std::uint32_t unfinished_ = 0;
    std::atomic<int> idle_{0};
    std::exception_ptr error_;
};

// Runs a and b: b on another thread if one takes it before a is done, else here. Either
// way the results are the same; only the time differs
template <class A, class B>
void fork_join(Scheduler* scheduler, const A& a, const B& b) {
    if (!scheduler || !scheduler->has_idle()) {
        a();
        b();
        return;
    }
    struct State {
        std::atomic<bool> taken{false}, done{false};
    };
    const auto state = std::make_shared<State>();
    scheduler->push([state, &b] {
        if (state->taken.exchange(true)) return;
        struct Done {
            State& s;
            ~Done() { s.done.store(true, std::memory_order_release); }
        } done{*state};
        b();
    });
    // b lives in this frame: once another thread has taken it, wait for it, also when a
    // throws
    const auto wait = [&] {
        while (!state->done.load(std::memory_order_acquire))
            std::this_thread::yield();
    };
    try {
        a();
    } catch (...) {
        if (state->taken.exchange(true)) wait();
        throw;
    }
    if (!state->taken.exchange(true)) return b();
    wait();
}

}  // namespace raylab::bvh_build
