"""Hill-climbs a linear policy on ubersim's GoToBall task, seen through emulated vision."""
import sys

import numpy as np
from ubersim.envs import GoToBallEnv

iterations = int(sys.argv[1]) if len(sys.argv) > 1 else 30
env = GoToBallEnv(vision_profile="cmdragons02", radio_profile="cmdragons02")
rng = np.random.default_rng(0)


def episode_return(weights, seed):
    obs, _ = env.reset(seed=seed)
    total = 0.0
    for _ in range(200):  # 5 s of play in 25 ms steps
        obs, reward, terminated, truncated, _ = env.step(np.tanh(weights @ obs))
        total += reward
        if terminated or truncated:
            break
    return total


best = np.zeros((3, 9))  # action (vx, vy, omega) = tanh(W obs)
best_score = np.mean([episode_return(best, seed) for seed in range(3)])
for iteration in range(iterations):
    candidate = best + 0.3 * rng.standard_normal(best.shape)
    score = np.mean([episode_return(candidate, seed) for seed in range(3)])
    if score > best_score:
        best, best_score = candidate, score
    print(f"iteration {iteration}: best mean return {best_score:.3f}")
